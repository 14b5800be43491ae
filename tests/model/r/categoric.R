# Categoric factors in a response-surface model, as R's lm computes them with sum-to-zero
# (contr.sum) coding: reference for tests/model/test_categoric_r.py.
# Model (Design-Expert's "quadratic" with categoric factors): main effects of every factor,
# every two-factor interaction (numeric x categoric and categoric x categoric included),
# pure squares of the numeric factors only. Numeric factors are coded -1..+1 from their
# observed minimum and maximum; categoric levels are in order of first appearance.
# Type III (partial) SS of a term: the extra SS of dropping all of its columns at once.
#   Rscript tests/model/r/categoric.R      (from the repository root or from this folder)
here <- if (file.exists("cat_bbd3x2.csv")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
g <- function(x) sprintf("%.17g", x)
cases <- list(
  list(name = "cat_bbd3x2", y = "yield_pct", num = c("temp_c", "time_min", "conc_pct"), cat = c("supplier"),
       new = data.frame(temp_c = c(140, 165), time_min = c(25, 38), conc_pct = c(6.5, 3.5), supplier = c("south", "north"))),
  list(name = "cat_ccd2x3", y = "wear_um", num = c("speed_m_s", "load_n"), cat = c("lubricant"),
       new = data.frame(speed_m_s = c(0.45, 0.58, 0.5), load_n = c(700, 950, 800), lubricant = c("grease", "mineral", "synthetic"))),
  list(name = "cat_f2x2x3", y = "y", num = c("x1", "x2"), cat = c("stage", "material"),
       new = data.frame(x1 = c(1.5, 2.7), x2 = c(37, 44), stage = c("rms", "rfcms"), material = c("polymer", "bronze")))
)
coef_out <- c("dataset,column,estimate,std_error")
anova_out <- c("dataset,source,df,sum_sq,f,p")
stat_out <- c("dataset,stat,value")
pred_out <- c("dataset,row,fit,ci_low,ci_high,pi_low,pi_high")
for (cs in cases) {
  d0 <- read.csv(file.path(here, paste0(cs$name, ".csv")), stringsAsFactors = FALSE)
  d <- d0[!is.na(d0[[cs$y]]), ]
  L <- LETTERS[seq_len(length(cs$num) + length(cs$cat))]
  X <- data.frame(y = d[[cs$y]])
  nw <- data.frame(row = seq_len(nrow(cs$new)))
  for (i in seq_along(cs$num)) {
    v <- d0[[cs$num[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (d[[cs$num[i]]] - (lo + hi) / 2) / ((hi - lo) / 2)
    nw[[L[i]]] <- (cs$new[[cs$num[i]]] - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  for (j in seq_along(cs$cat)) {
    lv <- unique(d0[[cs$cat[j]]])
    X[[L[length(cs$num) + j]]] <- factor(d[[cs$cat[j]]], levels = lv)
    nw[[L[length(cs$num) + j]]] <- factor(cs$new[[cs$cat[j]]], levels = lv)
  }
  sq <- paste0("I(", L[seq_along(cs$num)], "^2)", collapse = " + ")
  f <- as.formula(paste0("y ~ (", paste(L, collapse = " + "), ")^2 + ", sq))
  m <- lm(f, data = X)
  s <- summary(m)
  co <- s$coefficients
  for (t in rownames(co)) coef_out <- c(coef_out, paste(cs$name, paste0("\"", t, "\""), g(co[t, 1]), g(co[t, 2]), sep = ","))
  mm <- model.matrix(m)
  asg <- attr(mm, "assign")
  labs <- attr(terms(m), "term.labels")
  rss <- deviance(m); dfr <- df.residual(m); mse <- rss / dfr
  for (k in seq_along(labs)) {
    keep <- asg != k
    rss0 <- sum(lm.fit(mm[, keep, drop = FALSE], X$y)$residuals^2)
    ss <- rss0 - rss; df <- sum(asg == k)
    fv <- (ss / df) / mse
    anova_out <- c(anova_out, paste(cs$name, paste0("\"", labs[k], "\""), df, g(ss), g(fv), g(pf(fv, df, dfr, lower.tail = FALSE)), sep = ","))
  }
  tss <- sum((X$y - mean(X$y))^2)
  anova_out <- c(anova_out, paste(cs$name, "Model", ncol(mm) - 1, g(tss - rss), g(((tss - rss) / (ncol(mm) - 1)) / mse),
                                  g(pf(((tss - rss) / (ncol(mm) - 1)) / mse, ncol(mm) - 1, dfr, lower.tail = FALSE)), sep = ","))
  anova_out <- c(anova_out, paste(cs$name, "Residual", dfr, g(rss), "NA", "NA", sep = ","))
  key <- do.call(paste, c(lapply(c(cs$num, cs$cat), function(v) d[[v]]), sep = "|"))
  pe <- lm(X$y ~ factor(key))
  dfpe <- df.residual(pe); sspe <- deviance(pe)
  if (dfpe > 0) {
    fl <- ((rss - sspe) / (dfr - dfpe)) / (sspe / dfpe)
    anova_out <- c(anova_out, paste(cs$name, "Lack of Fit", dfr - dfpe, g(rss - sspe), g(fl), g(pf(fl, dfr - dfpe, dfpe, lower.tail = FALSE)), sep = ","))
    anova_out <- c(anova_out, paste(cs$name, "Pure Error", dfpe, g(sspe), "NA", "NA", sep = ","))
  }
  h <- hatvalues(m)
  press <- sum((residuals(m) / (1 - h))^2)
  stat_out <- c(stat_out, paste(cs$name, "press", g(press), sep = ","), paste(cs$name, "r2", g(s$r.squared), sep = ","),
                paste(cs$name, "adj_r2", g(s$adj.r.squared), sep = ","), paste(cs$name, "pred_r2", g(1 - press / tss), sep = ","),
                paste(cs$name, "sigma", g(s$sigma), sep = ","))
  pc <- predict(m, newdata = nw, interval = "confidence")
  pp <- predict(m, newdata = nw, interval = "prediction")
  for (r in seq_len(nrow(nw))) pred_out <- c(pred_out, paste(cs$name, r, g(pc[r, 1]), g(pc[r, 2]), g(pc[r, 3]), g(pp[r, 2]), g(pp[r, 3]), sep = ","))
}
writeLines(coef_out, file.path(here, "categoric_coef_expected.csv"))
writeLines(anova_out, file.path(here, "categoric_anova_expected.csv"))
writeLines(stat_out, file.path(here, "categoric_stats_expected.csv"))
writeLines(pred_out, file.path(here, "categoric_pred_expected.csv"))
cat(R.version.string, "\n")
