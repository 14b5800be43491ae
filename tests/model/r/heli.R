# R rsm 2.10 and MASS on rsm's own data set `heli` (Box & Draper, helicopter flight time; a
# 4-factor CCD in 2 blocks, 30 runs): the reference for tests/model/test_r_heli.py.
# The data are written decoded (actual units A, R, W, L) to heli.csv; the model is coded from the
# observed minimum and maximum of each column (rsm-lrg's default), x = (v - mid) / half-range,
# and blocks are sum-to-zero (contr.sum), as rsm-lrg reports them.
#   Rscript tests/model/r/heli.R      (run from the repository root or from this folder)
suppressMessages({library(rsm); library(MASS)})
here <- if (file.exists("heli.R")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
d <- decode.data(heli)
d <- data.frame(block = as.integer(as.character(d$block)), A = d$A, R = d$R, W = d$W, L = d$L,
                ave = d$ave, logSD = d$logSD)
write.csv(d, file.path(here, "heli.csv"), row.names = FALSE, quote = FALSE)
lo <- sapply(d[c("A", "R", "W", "L")], min); hi <- sapply(d[c("A", "R", "W", "L")], max)
mid <- (lo + hi) / 2; half <- (hi - lo) / 2
cd <- coded.data(d, x1 ~ (A - 12.4) / 1.2, x2 ~ (R - 2.52) / 0.52, x3 ~ (W - 1.25) / 0.5, x4 ~ (L - 2) / 1)
stopifnot(all.equal(unname(mid), c(12.4, 2.52, 1.25, 2)), all.equal(unname(half), c(1.2, 0.52, 0.5, 1)))
cd$block <- factor(cd$block); contrasts(cd$block) <- contr.sum(2)
m <- rsm(ave ~ block + SO(x1, x2, x3, x4), data = cd)
out <- c("quantity,key,value")
add <- function(q, k, v) out <<- c(out, paste(q, k, g(v), sep = ","))
b <- coef(m)
names(b) <- sub("^(FO|TWI|PQ)\\(x1, x2, x3, x4\\)", "", names(b))
keys <- c("(Intercept)" = "Intercept", "x1" = "A", "x2" = "B", "x3" = "C", "x4" = "D",
          "x1:x2" = "AB", "x1:x3" = "AC", "x1:x4" = "AD", "x2:x3" = "BC", "x2:x4" = "BD", "x3:x4" = "CD",
          "x1^2" = "A^2", "x2^2" = "B^2", "x3^2" = "C^2", "x4^2" = "D^2", "block1" = "block1")
for (t in names(b)) add("coef_coded", keys[[t]], b[[t]])
s <- summary(m)
se <- s$coefficients[, "Std. Error"]; names(se) <- names(b)
for (t in names(b)) add("se_coded", keys[[t]], se[[t]])
# partial (Type III) sums of squares of each term; residual, lack of fit, pure error
cdf <- as.data.frame(cd)
lmm <- lm(ave ~ block + x1 + x2 + x3 + x4 + x1:x2 + x1:x3 + x1:x4 + x2:x3 + x2:x4 + x3:x4 +
            I(x1^2) + I(x2^2) + I(x3^2) + I(x4^2), data = cdf)  # the same model, written out
stopifnot(isTRUE(all.equal(unname(fitted(lmm)), unname(fitted(m)))))
# partial SS: RSS without that one column of the model matrix minus the full RSS (drop1 keeps
# marginality and so gives no SS for a main effect that sits in an interaction)
X <- model.matrix(lmm); rss <- function(X) sum(lm.fit(X, cdf$ave)$residuals^2)
partial <- function(t) rss(X[, colnames(X) != t, drop = FALSE]) - rss(X)
dk <- c("x1" = "A", "x2" = "B", "x3" = "C", "x4" = "D", "x1:x2" = "AB", "x1:x3" = "AC", "x1:x4" = "AD",
        "x2:x3" = "BC", "x2:x4" = "BD", "x3:x4" = "CD", "I(x1^2)" = "A^2", "I(x2^2)" = "B^2",
        "I(x3^2)" = "C^2", "I(x4^2)" = "D^2")
for (t in names(dk)) add("partial_ss", dk[[t]], partial(t))
lof <- s$lof
add("anova_ss", "Residual", lof["Residuals", "Sum Sq"]); add("anova_df", "Residual", lof["Residuals", "Df"])
add("anova_ss", "Lack of Fit", lof["Lack of fit", "Sum Sq"]); add("anova_df", "Lack of Fit", lof["Lack of fit", "Df"])
add("anova_ss", "Pure Error", lof["Pure error", "Sum Sq"]); add("anova_df", "Pure Error", lof["Pure error", "Df"])
add("anova_p", "Lack of Fit", lof["Lack of fit", "Pr(>F)"])
add("anova_ss", "Block", lof["block", "Sum Sq"])
cn <- canonical(m, threshold = 0)
for (i in 1:4) add("stationary_coded", c("A", "B", "C", "D")[i], cn$xs[[i]])
for (i in 1:4) add("stationary_actual", c("A", "R", "W", "L")[i], cn$xs[[i]] * half[[i]] + mid[[i]])
for (i in 1:4) add("eigenvalue", i, cn$eigen$values[[i]])
# the surface averaged over the blocks (sum-to-zero: the block term is 0 there)
pred0 <- function(x) predict(m, newdata = data.frame(x1 = x[1], x2 = x[2], x3 = x[3], x4 = x[4],
                                                      block = factor("1", levels = c("1", "2")))) - b[["block1"]]
add("stationary_predicted", "ave", pred0(cn$xs))
# steepest ascent (ridge) path at radii 0, 0.5, 1
st <- steepest(m, dist = c(0, 0.5, 1))
for (i in seq_len(nrow(st))) for (j in 1:4)
  add(paste0("ridge_coded_", st$dist[i]), c("A", "B", "C", "D")[j], st[i, paste0("x", j)])
# the per-run diagnostics
for (i in c(1, 5, 17, 19, 27)) {
  add("leverage", i, hatvalues(lmm)[[i]]); add("ext_studentized", i, rstudent(lmm)[[i]])
  add("cooks", i, cooks.distance(lmm)[[i]]); add("dffits", i, dffits(lmm)[[i]])
}
# Box-Cox on the same model: lambda by maximum likelihood on a 1e-4 grid over -3..3 and its
# 95 % likelihood-ratio interval (the grid ends at 3: the upper end is the grid's end)
bc <- boxcox(lmm, lambda = seq(-3, 3, by = 1e-4), plotit = FALSE)
add("boxcox", "lambda", bc$x[which.max(bc$y)])
ci <- bc$x[bc$y > max(bc$y) - qchisq(0.95, 1) / 2]
add("boxcox", "ci_low", min(ci))
writeLines(out, file.path(here, "heli_expected.csv"))
print(s)
