# The regression core against R rsm 2.10.6 / lm (reference for tests/model/test_core.py):
# a 4-factor CCD (coded data, offset 1e4) fitted with SO(); coefficients, the sequential
# sums of squares of rsm's summary (FO, TWI, PQ), lack of fit and pure error, PRESS, the
# hat diagonal and the VIF (diagonal of the inverse correlation matrix of the term columns).
#   Rscript tests/model/r/core_check.R      (run from the repository root or from this folder)
suppressMessages(library(rsm))
here <- if (file.exists("core_ccd4.csv")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
d <- read.csv(file.path(here, "core_ccd4.csv"))
m <- rsm(y ~ SO(x1, x2, x3, x4), data = d)
out <- c("quantity,name,value")
b <- coef(m)
for (t in names(b)) out <- c(out, paste("coef", paste0("\"", t, "\""), g(b[[t]]), sep = ","))
lof <- summary(m)$lof
for (src in rownames(lof)) {
  out <- c(out, paste("ss", paste0("\"", src, "\""), g(lof[src, "Sum Sq"]), sep = ","))
  out <- c(out, paste("df", paste0("\"", src, "\""), g(lof[src, "Df"]), sep = ","))
}
h <- hatvalues(m)
out <- c(out, paste("press", "PRESS", g(sum((resid(m) / (1 - h))^2)), sep = ","))
for (i in seq_along(h)) out <- c(out, paste("hat", i, g(h[[i]]), sep = ","))
X <- model.matrix(m)[, -1]
v <- diag(solve(cor(X)))
for (t in names(v)) out <- c(out, paste("vif", paste0("\"", t, "\""), g(v[[t]]), sep = ","))
writeLines(out, file.path(here, "core_expected.csv"))
print(lof)
cat(R.version.string, "; rsm", as.character(packageVersion("rsm")), "\n")
