# The vinyl mixture-process split-plot (Kowalski, Cornell & Vining 2002; daewr's `vinyl`,
# Lawson, Design and Analysis of Experiments with R, ch. 11) fitted by REML: reference for
# tests/model/engines/test_mixture_reml.py.
#   Rscript tests/model/r/mixture_vinyl.R   (from the repository root or this folder)
# Data: mixture_vinyl.csv, written from daewr's data/vinyl.rda (github cran/daewr 8fb3ef9) by
#   load("vinyl.rda"); write.csv(vinyl, "mixture_vinyl.csv", row.names = FALSE)
# 10 whole plots (WP: one blend of plasticisers x1, x2, x3 each, made once), 4 runs of the
# 2^2 process factorial (z1 extrusion rate, z2 drying temperature, coded -1/+1) in each.
# The Scheffe model on L-pseudo components A = (x1 - 0.47)/0.38, B = x2/0.38,
# C = (x3 - 0.15)/0.38 (the observed minima, as rsm-lrg codes a bare --component), the
# process factors D = z1, E = z2 as they are (-1..+1):
#   "kcv"   : y ~ 0 + (A + B + C) * (1 + D + E + D:E) + (1|WP)   (12 fixed effects)
#   "cross" : y ~ 0 + (A + B + C) * (1 + D + E) + (1|WP)         (9; rsm-lrg's mixture-linear
#             model crossed with the process main effects)
#   "ssp"   : mixture_ssp.csv (make_mixture_ssp.py: simulated; 4 days x 3 batches, one blend per
#             batch, the 2^2 process factorial in each), components from 0 (A = x1, ...):
#             y ~ 0 + (A + B + C + A:B + A:C + B:C) * (1 + D + E) + (1|day) + (1|batch)
#             (rsm-lrg's mixture-quadratic crossed with the process main effects, two random effects)
# Fixed effects, SEs, variance components: lme4::lmer(REML = TRUE), bobyqa rhoend 1e-12, and
# nlme::lme(method = "REML") as a second route. Kenward-Roger: pbkrtest::KRmodcomp(fit, L):
# "Linear Mixture" L = the q - 1 contrasts A - C, B - C (equal linear blending), every other
# term its own column.
# R 4.2.2, lme4 1.1-31, nlme 3.1-162, pbkrtest 0.5.2.
suppressMessages({library(lme4); library(pbkrtest); library(nlme)})
here <- if (file.exists("mixture_vinyl.csv")) "." else "tests/model/r"
g <- function(x) sprintf("%.17g", x)
v <- read.csv(file.path(here, "mixture_vinyl.csv"))
r <- 1 - 0.47 - 0 - 0.15
vinyl <- data.frame(y = v$y, A = (v$x1 - 0.47) / r, B = v$x2 / r, C = (v$x3 - 0.15) / r, D = v$z1, E = v$z2,
                    WP = factor(v$WP))
s3 <- read.csv(file.path(here, "mixture_ssp.csv"))
ssp <- data.frame(y = s3$y, A = s3$x1, B = s3$x2, C = s3$x3, D = s3$z1, E = s3$z2, day = factor(s3$day),
                  batch = factor(s3$batch))
quad <- c("A", "B", "C", "A:B", "A:C", "B:C")
models <- list(
  kcv = list(d = vinyl, f = y ~ 0 + A + B + C + A:D + A:E + B:D + B:E + C:D + C:E + A:D:E + B:D:E + C:D:E,
             re = "WP"),
  cross = list(d = vinyl, f = y ~ 0 + A + B + C + A:D + A:E + B:D + B:E + C:D + C:E, re = "WP"),
  ssp = list(d = ssp, f = as.formula(paste("y ~ 0 +", paste(c(quad, paste0(quad, ":D"), paste0(quad, ":E")),
                                                            collapse = " + "))), re = c("day", "batch")))
ctl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e5))
coef_out <- c("model,column,estimate,std_error,estimate_nlme,std_error_nlme")
vc_out <- c("model,component,variance,variance_nlme")
kr_out <- c("model,term,num_df,den_df,f,p")
for (nm in names(models)) {
  cs <- models[[nm]]; f <- cs$f; d <- cs$d
  ranef_terms <- paste0("(1 | ", cs$re, ")", collapse = " + ")
  m <- lmer(update(f, as.formula(paste(". ~ . +", ranef_terms))), data = d, REML = TRUE, control = ctl)
  rand <- if (length(cs$re) == 1) as.formula(paste("~ 1 |", cs$re)) else
    eval(parse(text = paste0("list(", paste0(cs$re, " = ~ 1", collapse = ", "), ")")))
  m2 <- lme(f, random = rand, data = d, method = "REML", control = lmeControl(tolerance = 1e-12, msTol = 1e-12))
  b <- fixef(m); se <- sqrt(diag(as.matrix(vcov(m))))
  b2 <- fixef(m2); se2 <- sqrt(diag(m2$varFix))
  for (j in seq_along(b))
    coef_out <- c(coef_out, paste(nm, gsub(":", "", names(b)[j]), g(b[j]), g(se[j]), g(b2[j]), g(se2[j]), sep = ","))
  vc <- as.data.frame(VarCorr(m))
  # nlme's VarCorr prints rounded text: the variances from the fitted relative precision factors
  vc2 <- c(sapply(m2$modelStruct$reStruct, function(x) m2$sigma^2 * as.numeric(as.matrix(x))),
           Residual = m2$sigma^2)
  for (gname in c(cs$re, "Residual")) {
    ours <- if (gname == "Residual") "residual" else if (nm == "ssp") gname else "whole_plot"
    vc_out <- c(vc_out, paste(nm, ours, g(vc$vcov[vc$grp == gname]), g(vc2[[gname]]), sep = ","))
  }
  cols <- names(b); p <- length(cols)
  Llin <- rbind(as.numeric(cols == "A") - as.numeric(cols == "C"), as.numeric(cols == "B") - as.numeric(cols == "C"))
  tests <- list("Linear Mixture" = Llin)
  for (cn in cols[!(cols %in% c("A", "B", "C"))]) tests[[gsub(":", "", cn)]] <- matrix(as.numeric(cols == cn), 1)
  for (tn in names(tests)) {
    kr <- KRmodcomp(m, tests[[tn]])$test["Ftest", ]
    kr_out <- c(kr_out, paste(nm, paste0('"', tn, '"'), kr$ndf, g(kr$ddf), g(kr$stat), g(kr$p.value), sep = ","))
  }
}
writeLines(coef_out, file.path(here, "mixture_vinyl_coef_expected.csv"))
writeLines(vc_out, file.path(here, "mixture_vinyl_vc_expected.csv"))
writeLines(kr_out, file.path(here, "mixture_vinyl_kr_expected.csv"))
