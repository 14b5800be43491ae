# REML fits whose random-intercept variance is estimated at zero (the boundary), and their
# Kenward-Roger F tests with the zero component kept in the computation, as pbkrtest keeps it:
# reference for tests/model/engines/test_mixed_boundary.py.
#   Rscript tests/model/r/mixed_boundary.R   (from the repository root or this folder)
# R 4.2.2, lme4 1.1-31, pbkrtest 0.5.2, lmerTest 3.1-3 (Debian r-cran-* packages).
# Data:
#   mixed_apple.csv  - daewr `apple` (Lawson 2015, Design and Analysis of Experiments with R,
#                      CRC; the confounded apple-slice browning experiment): 4 blocks of 6, A (4
#                      levels) x B (3 levels), blocks random; model A + B + A:B. lme4 puts the
#                      block variance at 0 ("boundary (singular) fit").
#   mixed_sp_zero.csv, mixed_sp_small.csv - made by make_mixed.py: 8 whole plots x 4 runs, no
#                      whole-plot effect / a small one (sd 0.5); quadratic in 4 factors.
# KR: KRmodcomp(lmer fit, L), L the rows selecting a term's columns (Type III), and lmerTest's
# anova(ddf = "Kenward-Roger") as a second route.
suppressMessages({library(lme4); library(pbkrtest); library(lmerTest)})
here <- if (file.exists("mixed_apple.csv")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
g <- function(x) sprintf("%.17g", x)
cases <- list(
  list(name = "mixed_apple", y = "rating", wp = "Block", num = character(0), cat = c("A", "B"), order = 2),
  list(name = "mixed_sp_zero", y = "wear_um", wp = "whole_plot", num = c("temp_c", "preload_kn", "speed_m_s", "lube_ml"),
       cat = character(0), order = 2),
  list(name = "mixed_sp_small", y = "wear_um", wp = "whole_plot", num = c("temp_c", "preload_kn", "speed_m_s", "lube_ml"),
       cat = character(0), order = 2)
)
kr_out <- c("dataset,term,num_df,den_df,f,p,den_df_lmertest,f_lmertest,p_lmertest")
pred_out <- c("dataset,A,B,C,D,estimate,std_error,den_df")
# prediction points (coded) for the mean's Kenward-Roger standard error and den df (lmerTest contest1D)
pts <- data.frame(A = c(0, 1, -1, 0.5, -0.3), B = c(0, -1, 1, 0.25, 0.9), C = c(0, 1, 0, -0.5, -1),
                  D = c(0, 0, -1, 0.75, 0.1))
vc_out <- c("dataset,component,lmer")
for (cs in cases) {
  d <- read.csv(file.path(here, paste0(cs$name, ".csv")), stringsAsFactors = FALSE)
  L <- LETTERS[seq_len(length(cs$num) + length(cs$cat))]
  X <- data.frame(y = d[[cs$y]], wp = factor(d[[cs$wp]]))
  for (i in seq_along(cs$num)) {
    v <- d[[cs$num[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  for (j in seq_along(cs$cat)) X[[L[length(cs$num) + j]]] <- factor(d[[cs$cat[j]]], levels = unique(d[[cs$cat[j]]]))
  rhs <- paste0("(", paste(L, collapse = " + "), ")^", cs$order)
  if (length(cs$num)) rhs <- paste(rhs, "+", paste0("I(", L[seq_along(cs$num)], "^2)", collapse = " + "))
  f <- as.formula(paste("y ~", rhs))
  l <- suppressMessages(lme4::lmer(update(f, . ~ . + (1 | wp)), data = X, REML = TRUE,
            control = lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5))))
  lt <- suppressMessages(lmerTest::lmer(update(f, . ~ . + (1 | wp)), data = X, REML = TRUE,
            control = lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5))))
  cat(cs$name, "theta", getME(l, "theta"), "\n")
  vl <- as.data.frame(VarCorr(l))$vcov
  vc_out <- c(vc_out, paste(cs$name, "group", g(vl[1]), sep = ","), paste(cs$name, "residual", g(vl[2]), sep = ","))
  at <- anova(lt, ddf = "Kenward-Roger", type = 3)
  if (length(cs$num) == 4) {
    Lp <- model.matrix(delete.response(terms(f)), pts)
    for (i in seq_len(nrow(pts))) {
      ct <- contest1D(lt, Lp[i, ], ddf = "Kenward-Roger")
      pred_out <- c(pred_out, paste(cs$name, g(pts$A[i]), g(pts$B[i]), g(pts$C[i]), g(pts$D[i]), g(ct$Estimate),
                                    g(ct[["Std. Error"]]), g(ct$df), sep = ","))
    }
  }
  mm <- model.matrix(f, X)
  asg <- attr(mm, "assign")
  labs <- attr(terms(f), "term.labels")
  for (k in seq_along(labs)) {
    cols <- which(asg == k)
    Lm <- matrix(0, length(cols), ncol(mm))
    Lm[cbind(seq_along(cols), cols)] <- 1
    kr <- KRmodcomp(l, Lm)$test  # one term
    kr_out <- c(kr_out, paste(cs$name, paste0("\"", labs[k], "\""), kr["Ftest", "ndf"], g(kr["Ftest", "ddf"]),
                              g(kr["Ftest", "stat"]), g(kr["Ftest", "p.value"]),
                              g(at[labs[k], "DenDF"]), g(at[labs[k], "F value"]), g(at[labs[k], "Pr(>F)"]), sep = ","))
  }
}
writeLines(pred_out, file.path(here, "mixed_boundary_pred_expected.csv"))
writeLines(kr_out, file.path(here, "mixed_boundary_kr_expected.csv"))
writeLines(vc_out, file.path(here, "mixed_boundary_vc_expected.csv"))
