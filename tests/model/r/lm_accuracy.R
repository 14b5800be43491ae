# Coefficients of the quadratic model by R lm (QR, LINPACK dqrdc2) on the coded columns that
# rsm_lrg.fit uses (reference for tests/model/test_accuracy.py).
#   Rscript tests/model/r/lm_accuracy.R      (run from the repository root or from this folder)
here <- if (file.exists("lm_scales_coded.csv")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
out <- c("dataset,term,estimate")
names_de <- c("(Intercept)" = "Intercept", A = "A", B = "B", C = "C", "A:B" = "AB", "A:C" = "AC", "B:C" = "BC",
              "I(A^2)" = "A^2", "I(B^2)" = "B^2", "I(C^2)" = "C^2")
for (nm in c("lm_scales_coded", "lm_offset_coded")) {
  d <- read.csv(file.path(here, paste0(nm, ".csv")))
  m <- lm(y ~ A + B + C + A:B + A:C + B:C + I(A^2) + I(B^2) + I(C^2), data = d)
  b <- coef(m)
  for (t in names(b)) out <- c(out, paste(nm, names_de[[t]], g(b[[t]]), sep = ","))
}
writeLines(out, file.path(here, "lm_expected.csv"))
cat(R.version.string, "\n")
