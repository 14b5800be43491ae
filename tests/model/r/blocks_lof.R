# Lack of fit with blocks, as R rsm 2.10.6 computes it (reference for tests/model/test_blocks_lof.py).
# rsm's loftest() compares the model with lm(y ~ Block + PE(x1, ...)): pure error is the
# residual of blocks plus one mean per distinct factor setting.
#   Rscript tests/model/r/blocks_lof.R      (run from the repository root or from this folder)
suppressMessages(library(rsm))
here <- if (file.exists("blocks_bbd3.csv")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
cases <- list(
  list(name = "blocks_bbd3", formula = y ~ Block + SO(temp_c, time_min, conc_pct)),
  list(name = "blocks_ccd2", formula = y ~ Block + SO(p_bar, flow_l_min)),
  list(name = "blocks_fact3", formula = y ~ Block + FO(a_mm, b_s, c_k) + TWI(a_mm, b_s, c_k))
)
out <- c("dataset,source,df,sum_sq,f,p")
coefs <- c("dataset,term,estimate")
for (cs in cases) {
  d <- read.csv(file.path(here, paste0(cs$name, ".csv")))
  d$Block <- factor(d$Block)
  m <- rsm(cs$formula, data = d)
  lof <- summary(m)$lof
  # rows: Block, the model parts, Residuals, Lack of fit, Pure error
  for (src in c("Residuals", "Lack of fit", "Pure error")) {
    r <- lof[src, ]
    out <- c(out, paste(cs$name, src, r[["Df"]], g(r[["Sum Sq"]]), g(r[["F value"]]), g(r[["Pr(>F)"]]), sep = ","))
  }
  print(lof)
  b <- coef(m)
  for (t in names(b)) coefs <- c(coefs, paste(cs$name, paste0("\"", t, "\""), g(b[[t]]), sep = ","))
}
writeLines(out, file.path(here, "blocks_lof_expected.csv"))
# coefficients in actual units (Block: treatment contrasts, so only the factor terms compare)
writeLines(coefs, file.path(here, "blocks_coef_expected.csv"))
cat(R.version.string, "; rsm", as.character(packageVersion("rsm")), "\n")
