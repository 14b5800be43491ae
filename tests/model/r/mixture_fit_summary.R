# The mixture fit summary (rsm_lrg.fit_summary(..., components=...)) checked against R's lm and
# anova (tests/model/choice/test_mixture_fit_summary.py). Nested Scheffé models on L-pseudo-components
# (x' = (x - min x) / (T - sum min), T the median row sum, as rsm_lrg codes a bare component name):
# mean, linear, quadratic, special cubic, full cubic. Each sequential row is anova(previous, this):
# the extra sum of squares, F against the residual of the larger model (Design-Expert's layout);
# "Linear vs Mean" compares lm(y ~ 1) with lm(y ~ -1 + A + B + C), i.e. the linear model's SS about
# the mean on q - 1 = 2 df. Lack of fit: pure error of lm(y ~ factor(blend)). Statistics about the
# mean: std dev, R2, adjusted R2, predicted R2 = 1 - PRESS / SS_total(corrected), PRESS from hatvalues.
# Data: mixture_etch.csv (Myers & Montgomery, Table 12.4; mixexp's etch; 14 runs, replicated blends,
# the full cubic aliased: lm gives one NA coefficient) and mixture_pest.csv (daewr's pest, 13 blends,
# unreplicated). Run: Rscript mixture_fit_summary.R (writes mixture_fit_summary_expected.csv).
rows <- list()
add <- function(set, model, quantity, value) {
  rows[[length(rows) + 1]] <<- data.frame(set = set, model = model, quantity = quantity,
                                          value = sprintf("%.17g", value))
}
run <- function(set, d, y) {
  X <- as.matrix(d[, c("x1", "x2", "x3")])
  T <- median(rowSums(X))
  L <- apply(X, 2, min)
  P <- sweep(X, 2, L) / (T - sum(L))
  A <- P[, 1]; B <- P[, 2]; C <- P[, 3]
  n <- length(y)
  fits <- list(
    "mean" = lm(y ~ 1),
    "mixture-linear" = lm(y ~ -1 + A + B + C),
    "mixture-quadratic" = lm(y ~ -1 + A + B + C + A:B + A:C + B:C),
    "special-cubic" = lm(y ~ -1 + A + B + C + A:B + A:C + B:C + A:B:C),
    "mixture-cubic" = lm(y ~ -1 + A + B + C + A:B + A:C + B:C + A:B:C + I(A * B * (A - B)) +
                           I(A * C * (A - C)) + I(B * C * (B - C))))
  sst <- sum((y - mean(y))^2)
  blend <- factor(apply(round(X, 12), 1, paste, collapse = ","))
  pe <- lm(y ~ blend)
  df_pe <- df.residual(pe); ss_pe <- sum(resid(pe)^2)
  add(set, "mean", "ss", n * mean(y)^2)
  for (i in 2:length(fits)) {
    m <- names(fits)[i]
    a <- anova(fits[[i - 1]], fits[[i]])
    add(set, m, "seq_ss", a[2, "Sum of Sq"]); add(set, m, "seq_df", a[2, "Df"])
    add(set, m, "seq_f", a[2, "F"]); add(set, m, "seq_p", a[2, "Pr(>F)"])
    f <- fits[[i]]
    rss <- sum(resid(f)^2); dfr <- df.residual(f)
    h <- hatvalues(f)
    press <- sum((resid(f) / (1 - h))^2)
    add(set, m, "std_dev", sqrt(rss / dfr)); add(set, m, "r2", 1 - rss / sst)
    add(set, m, "adj_r2", 1 - (rss / dfr) / (sst / (n - 1)))
    add(set, m, "pred_r2", 1 - press / sst); add(set, m, "press", press)
    if (df_pe > 0) {
      dl <- dfr - df_pe; sl <- rss - ss_pe
      fl <- (sl / dl) / (ss_pe / df_pe)
      add(set, m, "lof_ss", sl); add(set, m, "lof_df", dl); add(set, m, "lof_f", fl)
      add(set, m, "lof_p", pf(fl, dl, df_pe, lower.tail = FALSE))
    }
  }
  if (df_pe > 0) { add(set, "pure error", "ss", ss_pe); add(set, "pure error", "df", df_pe) }
}
etch <- read.csv("mixture_etch.csv")
run("etch", etch, etch$erate)
pest <- read.csv("mixture_pest.csv")
run("pest", pest, pest$y)
out <- do.call(rbind, rows)
write.csv(out, "mixture_fit_summary_expected.csv", row.names = FALSE, quote = FALSE)
print(out)
