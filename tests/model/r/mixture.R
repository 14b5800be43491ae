# Scheffé mixture fits checked against R's lm (tests/model/test_mixture_fit.py).
# Data: mixexp's `etch` (Myers & Montgomery, Response Surface Methodology, 2002, Table 12.4:
# plasma etch rate of a three-component mixture, 14 runs, vertices and centroid replicated),
# loaded from the cran/mixexp package's data/etch.rda and written here in full precision
# (mixture_etch.csv). A second data set puts the same blends into a constrained region,
# x_i = L_i + (1 - sum L) x'_i with L = (0.1, 0.2, 0.05), so that the fit is on L-pseudo
# components (mixture_etch_l.csv). Run: Rscript mixture.R (writes mixture_expected.csv).
# The statistics R does not print for a no-intercept fit are computed here as
# Design-Expert defines them: about the mean.
etch <- read.csv("mixture_etch.csv")
lpd <- read.csv("mixture_etch_l.csv")
L <- c(0.1, 0.2, 0.05)
rows <- list()
add <- function(set, model, quantity, term, value) {
  rows[[length(rows) + 1]] <<- data.frame(set = set, model = model, quantity = quantity, term = term,
                                          value = sprintf("%.17g", value))
}
run <- function(set, d, real) {
  A <- (d$x1 - L[1] * real) / (1 - sum(L) * real)   # real = 1: L-pseudo, real = 0: as given
  B <- (d$x2 - L[2] * real) / (1 - sum(L) * real)
  C <- (d$x3 - L[3] * real) / (1 - sum(L) * real)
  y <- d$erate
  forms <- list("mixture-linear" = y ~ -1 + A + B + C,
                "mixture-quadratic" = y ~ -1 + A + B + C + A:B + A:C + B:C,
                "special-cubic" = y ~ -1 + A + B + C + A:B + A:C + B:C + A:B:C)
  sst <- sum((y - mean(y))^2)
  lin <- lm(y ~ -1 + A + B + C)
  for (m in names(forms)) {
    f <- lm(forms[[m]])
    s <- summary(f)$coefficients
    nm <- gsub(":", "", rownames(s))
    for (i in seq_along(nm)) {
      add(set, m, "coef", nm[i], s[i, 1])
      add(set, m, "se", nm[i], s[i, 2])
    }
    ssr <- sum(resid(f)^2)
    n <- length(y); p <- length(coef(f))
    add(set, m, "anova", "Residual", ssr)
    add(set, m, "anova", "Model", sst - ssr)
    add(set, m, "anova", "Cor Total", sst)
    add(set, m, "anova", "Linear Mixture", sst - sum(resid(lin)^2))
    # partial SS of each non-linear term: drop it, refit
    for (t in attr(terms(f), "term.labels")) {
      if (grepl(":", t)) {
        g <- update(f, as.formula(paste(". ~ . -", t)))
        add(set, m, "anova", gsub(":", "", t), sum(resid(g)^2) - ssr)
      }
    }
    # pure error: within-blend SS
    key <- paste(d$x1, d$x2, d$x3)
    pe <- sum((y - ave(y, key))^2)
    add(set, m, "anova", "Pure Error", pe)
    add(set, m, "anova", "Lack of Fit", ssr - pe)
    h <- hatvalues(f)
    press <- sum((resid(f) / (1 - h))^2)
    add(set, m, "stat", "r2", 1 - ssr / sst)
    add(set, m, "stat", "adj_r2", 1 - (ssr / (n - p)) / (sst / (n - 1)))
    add(set, m, "stat", "pred_r2", 1 - press / sst)
    add(set, m, "stat", "press", press)
    # the same model in the real proportions (sum x = 1 on every run): the actual coefficients
    x1 <- d$x1; x2 <- d$x2; x3 <- d$x3
    real <- list("mixture-linear" = y ~ -1 + x1 + x2 + x3,
                 "mixture-quadratic" = y ~ -1 + x1 + x2 + x3 + x1:x2 + x1:x3 + x2:x3,
                 "special-cubic" = y ~ -1 + x1 + x2 + x3 + x1:x2 + x1:x3 + x2:x3 + x1:x2:x3)
    fr <- lm(real[[m]])
    cr <- coef(fr)
    nm <- chartr("123", "ABC", gsub("x", "", gsub(":", "", names(cr))))
    for (i in seq_along(nm)) add(set, m, "actual", nm[i], cr[i])
    sr <- summary(fr)$coefficients[, 2]
    for (i in seq_along(nm)) add(set, m, "actual_se", nm[i], sr[i])
    # prediction and 95 % interval at the blend (0.3, 0.3, 0.4), as `confirm` reports it
    nd <- data.frame(x1 = 0.3, x2 = 0.3, x3 = 0.4)
    pr <- predict(fr, nd, interval = "prediction")
    add(set, m, "predict", "fit", pr[1, "fit"])
    add(set, m, "predict", "pi_low", pr[1, "lwr"])
    add(set, m, "predict", "pi_high", pr[1, "upr"])
  }
}
run("etch", etch, 0)
run("etch_l", lpd, 1)
write.csv(do.call(rbind, rows), "mixture_expected.csv", row.names = FALSE, quote = FALSE)

# Mixture-process: Cornell's fish-patty experiment (Experiments with Mixtures, 3rd ed., 2002,
# pp. 361-365; mixexp's `fishp`, in mixture_fishp.csv as shipped: blends printed to 5 decimals),
# the Scheffé quadratic in x1..x3 crossed with the linear process model in z1..z3 (24 terms).
fp <- read.csv("mixture_fishp.csv")
M <- with(fp, cbind(A = x1, B = x2, C = x3, AB = x1 * x2, AC = x1 * x3, BC = x2 * x3))
X <- cbind(M, M * fp$z1, M * fp$z2, M * fp$z3)
colnames(X) <- c(colnames(M), paste0(colnames(M), "D"), paste0(colnames(M), "E"), paste0(colnames(M), "F"))
y <- fp$y
f <- lm(y ~ -1 + X)
s <- summary(f)$coefficients
rows <- list()
nm <- sub("^X", "", rownames(s))
for (i in seq_along(nm)) {
  add("fishp", "mixture-quadratic", "coef", nm[i], s[i, 1])
  add("fishp", "mixture-quadratic", "se", nm[i], s[i, 2])
}
sst <- sum((y - mean(y))^2); ssr <- sum(resid(f)^2); n <- length(y); p <- ncol(X)
add("fishp", "mixture-quadratic", "anova", "Residual", ssr)
add("fishp", "mixture-quadratic", "anova", "Model", sst - ssr)
add("fishp", "mixture-quadratic", "anova", "Cor Total", sst)
add("fishp", "mixture-quadratic", "anova", "Linear Mixture", sst - sum(resid(lm(y ~ -1 + M[, 1:3]))^2))
for (j in 4:p) {
  g <- lm(y ~ -1 + X[, -j])
  add("fishp", "mixture-quadratic", "anova", colnames(X)[j], sum(resid(g)^2) - ssr)
}
h <- hatvalues(f)
press <- sum((resid(f) / (1 - h))^2)
add("fishp", "mixture-quadratic", "stat", "r2", 1 - ssr / sst)
add("fishp", "mixture-quadratic", "stat", "adj_r2", 1 - (ssr / (n - p)) / (sst / (n - 1)))
add("fishp", "mixture-quadratic", "stat", "pred_r2", 1 - press / sst)
# actual: x and z are the actual units here (z coded -1/+1 in the file, so the coding is identity)
write.csv(rbind(read.csv("mixture_expected.csv", colClasses = "character"), do.call(rbind, rows)),
          "mixture_expected.csv", row.names = FALSE, quote = FALSE)
