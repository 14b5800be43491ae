# Scheffé full cubic (mixture-cubic, terms AB(A-B)) and a --terms subset, checked against R's lm
# (tests/model/test_mixture_cubic.py). Run here: R_LIBS=/tmp/rlib Rscript mixture_cubic.R
# (writes mixture_pest.csv, mixture_polvdat.csv from the daewr package's data/*.rda when those
# files are beside this script, and mixture_cubic_expected.csv).
# Data (Lawson, Design and Analysis of Experiments with R, 2015, ch. 11; R package daewr):
#   pest    - pesticide formulation, three components, 13 blends (simplex-centroid-like with
#             interior check blends); the centroid is printed 0.33333 (sums to 0.99999).
#   polvdat - vinyl (polymer) formulation, constrained region x1 <= 0.8, x2 >= 0.1,
#             x3 >= 0.05 (Lawson's extreme vertices + centroid), 12 runs, centroid replicated
#             three times; fitted on L-pseudo components with L = (0, 0.1, 0.05).
# Cubic terms: cubic(a, b) = a^2 b - a b^2 = a b (a - b) (mixexp's `cubic`; Cornell, Experiments
# with Mixtures, 3rd ed., Eq. 2.11). The statistics R does not print for a no-intercept fit
# are computed as Design-Expert defines them: about the mean.
for (f in c("pest", "polvdat")) {
  if (file.exists(paste0(f, ".rda"))) {
    e <- new.env(); load(paste0(f, ".rda"), e)
    write.csv(format(get(f, e), digits = 17), paste0("mixture_", f, ".csv"), row.names = FALSE, quote = FALSE)
  }
}
rows <- list()
add <- function(set, model, quantity, term, value) {
  rows[[length(rows) + 1]] <<- data.frame(set = set, model = model, quantity = quantity, term = term,
                                          value = sprintf("%.17g", value))
}
cols <- function(A, B, C, which) {
  all <- cbind(A = A, B = B, C = C, AB = A * B, AC = A * C, BC = B * C, ABC = A * B * C,
               "AB(A-B)" = A * B * (A - B), "AC(A-C)" = A * C * (A - C), "BC(B-C)" = B * C * (B - C))
  all[, which, drop = FALSE]
}
MODELS <- list("mixture-cubic" = c("A", "B", "C", "AB", "AC", "BC", "ABC", "AB(A-B)", "AC(A-C)", "BC(B-C)"),
               "terms" = c("A", "B", "C", "AB", "AC", "BC", "AB(A-B)", "AC(A-C)"))
run <- function(set, d, L, model) {
  which <- MODELS[[model]]
  T <- 1
  R <- T - sum(L)
  X <- cols((d$x1 - L[1]) / R, (d$x2 - L[2]) / R, (d$x3 - L[3]) / R, which)
  y <- d$y
  f <- lm(y ~ -1 + X)
  s <- summary(f)$coefficients
  for (i in seq_along(which)) {
    add(set, model, "coef", which[i], s[i, 1])
    add(set, model, "se", which[i], s[i, 2])
  }
  n <- length(y); p <- ncol(X)
  sst <- sum((y - mean(y))^2); ssr <- sum(resid(f)^2)
  add(set, model, "anova", "Residual", ssr)
  add(set, model, "anova", "Model", sst - ssr)
  add(set, model, "anova", "Cor Total", sst)
  add(set, model, "anova", "Linear Mixture", sst - sum(resid(lm(y ~ -1 + X[, 1:3]))^2))
  for (j in 4:p) add(set, model, "anova", which[j], sum(resid(lm(y ~ -1 + X[, -j]))^2) - ssr)
  key <- paste(d$x1, d$x2, d$x3)
  pe <- sum((y - ave(y, key))^2)
  add(set, model, "anova", "Pure Error", pe)
  add(set, model, "anova", "Lack of Fit", ssr - pe)
  h <- hatvalues(f)
  press <- sum((resid(f) / (1 - h))^2)
  add(set, model, "stat", "r2", 1 - ssr / sst)
  add(set, model, "stat", "adj_r2", 1 - (ssr / (n - p)) / (sst / (n - 1)))
  add(set, model, "stat", "pred_r2", 1 - press / sst)
  add(set, model, "stat", "press", press)
  # the same model in the real proportions: the actual coefficients and their standard errors
  # (a real-proportion term set spans the same space only for the full cubic)
  if (model == "mixture-cubic") {
    Xr <- cols(d$x1, d$x2, d$x3, which)
    fr <- lm(y ~ -1 + Xr)
    sr <- summary(fr)$coefficients
    for (i in seq_along(which)) {
      add(set, model, "actual", which[i], sr[i, 1])
      add(set, model, "actual_se", which[i], sr[i, 2])
    }
  }
}
pest <- read.csv("mixture_pest.csv")
polv <- read.csv("mixture_polvdat.csv")
for (m in names(MODELS)) {
  run("pest", pest, c(0, 0, 0), m)
  run("polvdat", polv, c(0, 0.1, 0.05), m)
}
write.csv(do.call(rbind, rows), "mixture_cubic_expected.csv", row.names = FALSE, quote = FALSE)
