# REML fits with one random intercept (split-plot whole plots, random blocks) and their
# Kenward-Roger F tests: reference for tests/model/engines/test_mixed_r.py.
#   R_LIBS=/tmp/rlib Rscript tests/model/r/mixed.R   (from the repository root or this folder)
# R 4.2.2, nlme 3.1-162, lme4 1.1-31, pbkrtest 0.5.2 (Debian r-cran-* packages).
# Estimates, standard errors and variance components: nlme::lme(..., method = "REML") with
# tight convergence (nlme's defaults stop ~1e-6 short of the optimum on a flat likelihood),
# and lme4::lmer(REML = TRUE) as a second route. KR: pbkrtest::KRmodcomp(lmer fit, L) with L
# the rows selecting a term's columns (Type III: each term's columns jointly zero).
# Model "quadratic" (Design-Expert's, as rsm-lrg builds it): main effects, all two-factor
# interactions, squares of the numeric factors; numeric factors coded -1..+1 from their observed
# minimum and maximum; categoric factors sum-to-zero (contr.sum), levels in order of first appearance.
# Data: daewr (Lawson 2015, Design and Analysis of Experiments with R, CRC): cakeb (split-plot
# response surface, ch. 10: 4 oven runs of 2 or 3 cakes), pastry (blocked response surface,
# ch. 10: 7 blocks of 4, blocks random), splitPdes (cookie split-plot, ch. 8: whole plots =
# batch x shortening); mixed_sp_*.csv made by make_mixed.py.
suppressMessages({library(nlme); library(lme4); library(pbkrtest)})
here <- if (file.exists("mixed_cakeb.csv")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
g <- function(x) sprintf("%.17g", x)
cases <- list(
  list(name = "mixed_cakeb", y = "y", wp = "Ovenrun", num = c("x1", "x2"), cat = character(0), order = 2),
  list(name = "mixed_pastry", y = "y", wp = "Block", num = c("x1", "x2", "x3"), cat = character(0), order = 2),
  list(name = "mixed_cookie", y = "y", wp = "wp", num = character(0), cat = c("short", "trayT", "bakeT"), order = 3),
  list(name = "mixed_sp_bal", y = "wear_um", wp = "whole_plot", num = c("temp_c", "preload_kn", "speed_m_s", "lube_ml"),
       cat = character(0), order = 2),
  list(name = "mixed_sp_unbal", y = "wear_um", wp = "whole_plot", num = c("temp_c", "preload_kn", "speed_m_s"),
       cat = c("lube"), order = 2)
)
ctl <- lmeControl(msTol = 1e-15, tolerance = 1e-15, .relStep = 1e-9, msMaxIter = 1000, msMaxEval = 5000, niterEM = 100)
coef_out <- c("dataset,column,estimate,std_error,estimate_lmer,std_error_lmer")
vc_out <- c("dataset,component,nlme,lmer")
kr_out <- c("dataset,term,num_df,den_df,f,p")
for (cs in cases) {
  d <- read.csv(file.path(here, paste0(cs$name, ".csv")), stringsAsFactors = FALSE)
  L <- LETTERS[seq_len(length(cs$num) + length(cs$cat))]
  X <- data.frame(y = d[[cs$y]], wp = factor(d[[cs$wp]]))
  for (i in seq_along(cs$num)) {
    v <- d[[cs$num[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  for (j in seq_along(cs$cat)) X[[L[length(cs$num) + j]]] <- factor(d[[cs$cat[j]]], levels = unique(d[[cs$cat[j]]]))
  rhs <- paste0("(", paste(L, collapse = " + "), ")^", cs$order)
  if (length(cs$num)) rhs <- paste(rhs, "+", paste0("I(", L[seq_along(cs$num)], "^2)", collapse = " + "))
  f <- as.formula(paste("y ~", rhs))
  m <- lme(f, random = ~ 1 | wp, data = X, method = "REML", control = ctl)
  l <- lmer(update(f, . ~ . + (1 | wp)), data = X, REML = TRUE,
            control = lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5)))
  b <- fixef(m); se <- sqrt(diag(vcov(m))); bl <- fixef(l); sel <- sqrt(diag(as.matrix(vcov(l))))
  for (t in names(b)) coef_out <- c(coef_out, paste(cs$name, paste0("\"", t, "\""), g(b[t]), g(se[t]), g(bl[t]), g(sel[t]), sep = ","))
  vl <- as.data.frame(VarCorr(l))$vcov
  vc_out <- c(vc_out, paste(cs$name, "group", g(as.numeric(getVarCov(m))), g(vl[1]), sep = ","),
              paste(cs$name, "residual", g(m$sigma^2), g(vl[2]), sep = ","))
  mm <- model.matrix(f, X)
  asg <- attr(mm, "assign")
  labs <- attr(terms(f), "term.labels")
  for (k in seq_along(labs)) {
    cols <- which(asg == k)
    Lm <- matrix(0, length(cols), ncol(mm))
    Lm[cbind(seq_along(cols), cols)] <- 1
    kr <- KRmodcomp(l, Lm)$test
    kr_out <- c(kr_out, paste(cs$name, paste0("\"", labs[k], "\""), kr["Ftest", "ndf"], g(kr["Ftest", "ddf"]),
                              g(kr["Ftest", "stat"]), g(kr["Ftest", "p.value"]), sep = ","))
  }
}
writeLines(coef_out, file.path(here, "mixed_coef_expected.csv"))
writeLines(vc_out, file.path(here, "mixed_vc_expected.csv"))
writeLines(kr_out, file.path(here, "mixed_kr_expected.csv"))
