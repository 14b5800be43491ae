# Scheffe mixture models with fixed blocks fitted by least squares: reference for
# tests/model/test_mixture_fit_blocks.py.
#   Rscript tests/model/r/mixture_blocks.R   (from the repository root or this folder)
# Data (make_mixture_blocks.py: rsm-lrg's blocked D-optimal designs, responses simulated):
#   mixture_blocks_quad3.csv - 3 components, 3 blocks of 7, Scheffe quadratic;
#   mixture_blocks_proc3.csv - 3 components and a process factor t (20..40, coded -1..+1),
#                              2 blocks of 12, Scheffe quadratic crossed with t.
# L-pseudo components from the observed minima (A = (a - min a) / (1 - sum of minima)), as
# rsm-lrg codes a bare --component. Blocks: sum-to-zero contrasts (1 in block j, -1 in the
# last), numeric columns beside the Scheffe terms (no intercept).
# ANOVA as Design-Expert orders a blocked mixture: Block = SS of y ~ block about the mean;
# Linear Mixture = RSS(y ~ block) - RSS(y ~ block + linear blending); Model = RSS(y ~ block)
# - RSS(full); every non-linear term its partial SS (anova(full without it, full));
# pure error the residual of y ~ block + one mean per setting; lack of fit the rest.
# R 4.2.2 (stats::lm only).
here <- if (file.exists("mixture_blocks_quad3.csv")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
cases <- list(
  quad3 = list(terms = c("A", "B", "C", "A:B", "A:C", "B:C")),
  proc3 = list(terms = c("A", "B", "C", "A:B", "A:C", "B:C", "A:D", "B:D", "C:D", "A:B:D", "A:C:D", "B:C:D"))
)
coef_out <- c("dataset,term,estimate,std_error")
anova_out <- c("dataset,source,sum_sq,df,f,p")
for (nm in names(cases)) {
  v <- read.csv(file.path(here, paste0("mixture_blocks_", nm, ".csv")))
  lo <- c(min(v$a), min(v$b), min(v$c)); r <- 1 - sum(lo)
  d <- data.frame(y = v$y, A = (v$a - lo[1]) / r, B = (v$b - lo[2]) / r, C = (v$c - lo[3]) / r)
  if (!is.null(v$t)) d$D <- (v$t - 30) / 10
  nb <- max(v$block)
  bnames <- paste0("b", seq_len(nb - 1))
  for (j in seq_len(nb - 1)) d[[bnames[j]]] <- ifelse(v$block == j, 1, ifelse(v$block == nb, -1, 0))
  d$blockf <- factor(v$block)
  tm <- cases[[nm]]$terms
  rhs <- function(t) paste("0 +", paste(c(t, bnames), collapse = " + "))
  full <- lm(as.formula(paste("y ~", rhs(tm))), data = d)
  s <- summary(full)$coefficients
  for (t in tm) coef_out <- c(coef_out, paste(nm, gsub(":", "", t), g(s[t, 1]), g(s[t, 2]), sep = ","))
  f0 <- lm(y ~ blockf, data = d)
  fl <- lm(as.formula(paste("y ~", rhs(c("A", "B", "C")))), data = d)
  rss <- function(m) sum(residuals(m)^2)
  ms_res <- rss(full) / full$df.residual
  row <- function(src, ss, df, test = TRUE) {
    f <- if (test) (ss / df) / ms_res else NA
    p <- if (test) pf(f, df, full$df.residual, lower.tail = FALSE) else NA
    paste(nm, paste0('"', src, '"'), g(ss), df, g(f), g(p), sep = ",")
  }
  nonlin <- tm[grepl(":", tm)]
  anova_out <- c(anova_out, row("Model", rss(f0) - rss(full), length(tm) - 1),
                 row("Linear Mixture", rss(f0) - rss(fl), 2))
  for (t in nonlin) {
    red <- lm(as.formula(paste("y ~", rhs(setdiff(tm, t)))), data = d)
    anova_out <- c(anova_out, row(gsub(":", "", t), rss(red) - rss(full), 1))
  }
  setting <- factor(do.call(paste, d[intersect(c("A", "B", "C", "D"), names(d))]))
  pe <- lm(y ~ blockf + setting, data = d)
  df_pe <- pe$df.residual
  anova_out <- c(anova_out, row("Block", sum((fitted(f0) - mean(d$y))^2), nb - 1, FALSE),
                 row("Residual", rss(full), full$df.residual, FALSE))
  lof_ss <- rss(full) - rss(pe); lof_df <- full$df.residual - df_pe
  f_lof <- (lof_ss / lof_df) / (rss(pe) / df_pe)
  anova_out <- c(anova_out, paste(nm, '"Lack of Fit"', g(lof_ss), lof_df, g(f_lof),
                                  g(pf(f_lof, lof_df, df_pe, lower.tail = FALSE)), sep = ","),
                 row("Pure Error", rss(pe), df_pe, FALSE), row("Cor Total", sum((d$y - mean(d$y))^2), nrow(d) - 1, FALSE))
}
writeLines(coef_out, file.path(here, "mixture_blocks_coef_expected.csv"))
writeLines(anova_out, file.path(here, "mixture_blocks_anova_expected.csv"))
