# Independent Monte Carlo power for tests/model/test_power.py (issue 35, item 4): the same
# designs and simulated truth as rsm_lrg.model.power.simulate_power, drawn with R's own
# random numbers and analysed by R's own fits.
#
#   Rscript tests/model/r/power.R [DRAWS [SEED]]   (default 3000 draws, seed 20261128; the test's
#   constants pool the runs with seeds 20261128 and 20261129, 3000 draws each)
#
# Split plot: 8 whole plots of 4 runs, whole-plot factor A (+1/-1 alternately), sub-plot
#   factors B, C (a 2^2 in every whole plot); y = 0.5 (A + B + C) + u_wp + e, u_wp ~ N(0, eta),
#   eta = 1, e ~ N(0, 1); lmer(y ~ A + B + C + (1 | wp)) by REML, each coefficient's
#   Kenward-Roger F test at alpha 0.05: pbkrtest's vcovAdj once per draw, the den df by
#   pbkrtest's Lb_ddf, F = b_j^2 / PhiA_jj (one df: KR's F scaling is 1; the same numbers as
#   KRmodcomp(fit, L), which recomputes vcovAdj per call).
# Logistic: the 2^3 factorial replicated 6 times (48 runs); logit P(y = 1) = logit(0.3) +
#   0.5 (A + B + C); glm(binomial) and drop1(test = "LRT") per term at alpha 0.05. A draw
#   with separated outcomes (some fitted probability within 1e-6 of 0 or 1, or no
#   convergence) declares nothing significant, as rsm_lrg refuses to fit it.
suppressPackageStartupMessages({library(lme4); library(pbkrtest)})
args <- commandArgs(trailingOnly = TRUE)
N <- if (length(args)) as.integer(args[1]) else 3000L
set.seed(if (length(args) > 1) as.integer(args[2]) else 20261128L)
alpha <- 0.05

sp <- expand.grid(B = c(-1, 1), C = c(-1, 1), wp = 1:8)
sp$A <- ifelse(sp$wp %% 2 == 1, -1, 1)
sp$wp <- factor(sp$wp)
hits <- c(A = 0, B = 0, C = 0)
for (i in seq_len(N)) {
  u <- rnorm(8, 0, 1)
  sp$y <- 0.5 * (sp$A + sp$B + sp$C) + u[as.integer(sp$wp)] + rnorm(nrow(sp))
  fit <- suppressMessages(lmer(y ~ A + B + C + (1 | wp), data = sp, REML = TRUE))
  V0 <- vcov(fit); Va <- vcovAdj(fit); b <- fixef(fit)  # Va keeps its P and W for Lb_ddf
  p <- sapply(2:4, function(j) {
    L <- matrix(0, 1, 4); L[1, j] <- 1
    pf(b[j]^2 / as.matrix(Va)[j, j], 1, Lb_ddf(L, V0, Va), lower.tail = FALSE)
  })
  hits <- hits + (p < alpha)
}
cat(sprintf("split_plot %s %.6f\n", names(hits), hits / N), sep = "")

lg <- expand.grid(A = c(-1, 1), B = c(-1, 1), C = c(-1, 1))
lg <- lg[rep(seq_len(nrow(lg)), 6), ]
eta <- qlogis(0.3) + 0.5 * (lg$A + lg$B + lg$C)
hits <- c(A = 0, B = 0, C = 0)
separated <- 0
for (i in seq_len(N)) {
  lg$y <- rbinom(nrow(lg), 1, plogis(eta))
  fit <- suppressWarnings(glm(y ~ A + B + C, family = binomial, data = lg))
  f <- fitted(fit)
  if (!fit$converged || min(f) < 1e-6 || max(f) > 1 - 1e-6) {
    separated <- separated + 1
    next
  }
  p <- drop1(fit, test = "LRT")[c("A", "B", "C"), "Pr(>Chi)"]
  hits <- hits + (p < alpha)
}
cat(sprintf("logistic %s %.6f\n", names(hits), hits / N), sep = "")
cat(sprintf("logistic separated %.6f\n", separated / N))
