# REML fits with several random intercepts (nested and crossed) and their Kenward-Roger F
# tests: reference for tests/model/engines/test_mixed_several.py.
#   Rscript tests/model/r/mixed_several.R   (from the repository root or this folder)
# R 4.2.2, lme4 1.1-31, pbkrtest 0.5.2, lmerTest 3.1-3 (Debian r-cran-* packages).
# Estimates, standard errors and variance components: lme4::lmer(REML = TRUE) with tight
# convergence (bobyqa, rhoend 1e-12). KR: pbkrtest::KRmodcomp(lmer fit, L) with L the rows
# selecting a term's columns (Type III: each term's columns jointly zero), and lmerTest's
# anova(ddf = "Kenward-Roger") as a second route; the predicted mean's KR standard error and
# den df at a few coded points by lmerTest::contest1D.
# Numeric factors coded -1..+1 from their observed minimum and maximum; categoric factors
# sum-to-zero (contr.sum), levels in order of first appearance (as rsm-lrg codes them).
# Data:
#   mixed_cake.csv  - lme4 `cake` (Cook 1938; 15 replicates x 3 recipes x 6 temperatures):
#                     angle ~ recipe * temperature (both categoric) + (1|replicate) +
#                     (1|replicate:recipe).
#   mixed_oats.csv  - nlme `Oats` (Yates 1935; 6 blocks x 3 varieties (whole plots) x 4
#                     nitrogen levels): yield ~ Variety * nitro (nitro numeric) + (1|Block) +
#                     (1|Block:Variety).
#   mixed_ssp.csv   - made by make_mixed_several.py: a split-split-plot, subplots nested in whole
#                     plots (unique labels); linear + two-factor interactions in 4 factors; and
#                     (dataset mixed_ssp3) with the blocks of whole plots as a third effect.
#   mixed_strip.csv - made by make_mixed_several.py: a strip-plot, 8 rows crossed with 6 columns;
#                     quadratic in wash_min and dry_c with rpm (2 levels, no square).
suppressMessages({library(lme4); library(pbkrtest); library(lmerTest)})
here <- if (file.exists("mixed_cake.csv")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
g <- function(x) sprintf("%.17g", x)
cases <- list(
  list(name = "mixed_cake", y = "angle", num = character(0), cat = c("recipe", "temperature"), order = 2, sq = FALSE,
       re = c("replicate", "replicate:recipe")),
  list(name = "mixed_oats", y = "yield", num = "nitro", cat = "Variety", order = 2, sq = FALSE,
       re = c("Block", "Block:Variety")),
  list(name = "mixed_ssp", y = "wear_um", num = c("temp_c", "preload_kn", "speed_m_s", "lube_ml"), cat = character(0),
       order = 2, sq = FALSE, re = c("whole_plot", "subplot")),
  list(name = "mixed_ssp", tag = "mixed_ssp3", y = "wear_um", num = c("temp_c", "preload_kn", "speed_m_s", "lube_ml"),
       cat = character(0), order = 2, sq = FALSE, re = c("block", "whole_plot", "subplot")),
  list(name = "mixed_strip", y = "gloss", num = c("wash_min", "dry_c", "rpm"), cat = character(0), order = 2,
       sq = c(TRUE, TRUE, FALSE), re = c("row", "col"))
)
coef_out <- c("dataset,column,estimate,std_error")
vc_out <- c("dataset,component,variance")
kr_out <- c("dataset,term,num_df,den_df,f,p,den_df_lmertest,f_lmertest,p_lmertest")
pred_out <- c("dataset,A,B,C,D,estimate,std_error,den_df")
pts <- data.frame(A = c(0, 1, -1, 0.5, -0.3), B = c(0, -1, 1, 0.25, 0.9), C = c(0, 1, 0, -0.5, -1),
                  D = c(0, 0, -1, 0.75, 0.1))
ctl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5))
for (cs in cases) {
  if (is.null(cs$tag)) cs$tag <- cs$name
  d <- read.csv(file.path(here, paste0(cs$name, ".csv")), stringsAsFactors = FALSE)
  facs <- c(cs$num, cs$cat)  # numeric factors first, as rsm-lrg letters them
  L <- LETTERS[seq_along(facs)]
  X <- data.frame(y = d[[cs$y]])
  for (i in seq_along(facs)) {
    v <- d[[facs[i]]]
    if (facs[i] %in% cs$num) {
      lo <- min(v); hi <- max(v); X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
    } else X[[L[i]]] <- factor(v, levels = unique(v))
  }
  for (r in unique(unlist(strsplit(cs$re, ":")))) X[[r]] <- factor(d[[r]])
  rhs <- paste0("(", paste(L, collapse = " + "), ")^", cs$order)
  nl <- L[facs %in% cs$num]
  if (!identical(cs$sq, FALSE)) rhs <- paste(rhs, "+", paste0("I(", nl[cs$sq], "^2)", collapse = " + "))
  f <- as.formula(paste("y ~", rhs))
  fr <- update(f, as.formula(paste(". ~ . +", paste0("(1 | ", cs$re, ")", collapse = " + "))))
  l <- suppressMessages(lme4::lmer(fr, data = X, REML = TRUE, control = ctl))
  lt <- suppressMessages(lmerTest::lmer(fr, data = X, REML = TRUE, control = ctl))
  cat(cs$tag, "theta", getME(l, "theta"), "REMLcrit", REMLcrit(l), "\n")
  b <- fixef(l); se <- sqrt(diag(as.matrix(vcov(l))))
  for (t in names(b)) coef_out <- c(coef_out, paste(cs$tag, paste0("\"", t, "\""), g(b[t]), g(se[t]), sep = ","))
  vcd <- as.data.frame(VarCorr(l))
  for (i in seq_len(nrow(vcd)))
    vc_out <- c(vc_out, paste(cs$tag, if (vcd$grp[i] == "Residual") "residual" else vcd$grp[i], g(vcd$vcov[i]), sep = ","))
  at <- anova(lt, ddf = "Kenward-Roger", type = 3)
  mm <- model.matrix(f, X)
  asg <- attr(mm, "assign")
  labs <- attr(terms(f), "term.labels")
  for (k in seq_along(labs)) {
    cols <- which(asg == k)
    Lm <- matrix(0, length(cols), ncol(mm))
    Lm[cbind(seq_along(cols), cols)] <- 1
    kr <- KRmodcomp(l, Lm)$test
    kr_out <- c(kr_out, paste(cs$tag, paste0("\"", labs[k], "\""), kr["Ftest", "ndf"], g(kr["Ftest", "ddf"]),
                              g(kr["Ftest", "stat"]), g(kr["Ftest", "p.value"]),
                              g(at[labs[k], "DenDF"]), g(at[labs[k], "F value"]), g(at[labs[k], "Pr(>F)"]), sep = ","))
  }
  if (length(cs$cat) == 0) {
    P <- pts[, L, drop = FALSE]
    Lp <- model.matrix(delete.response(terms(f)), P)
    for (i in seq_len(nrow(P))) {
      ct <- contest1D(lt, Lp[i, ], ddf = "Kenward-Roger")
      pred_out <- c(pred_out, paste(cs$tag, g(pts$A[i]), g(pts$B[i]), g(pts$C[i]), g(pts$D[i]), g(ct$Estimate),
                                    g(ct[["Std. Error"]]), g(ct$df), sep = ","))
    }
  }
}
writeLines(coef_out, file.path(here, "mixed_several_coef_expected.csv"))
writeLines(vc_out, file.path(here, "mixed_several_vc_expected.csv"))
writeLines(kr_out, file.path(here, "mixed_several_kr_expected.csv"))
writeLines(pred_out, file.path(here, "mixed_several_pred_expected.csv"))
