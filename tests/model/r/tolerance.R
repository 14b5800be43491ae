# Regression tolerance intervals checked against R's tolerance::regtol.int (version 3.0.0,
# CRAN; tests/model/contract/test_tolerance_r.py). Three data sets already in this folder, none used to
# develop rsm_lrg.model.contract.tolerance:
#   heli         heli.csv, response `ave`, full quadratic in A, R, W, L (block column unused);
#   scales       lm_scales.csv, response log(y) (rsm-lrg: --transform log), full quadratic in
#                thickness_m, freq_hz, temp_c (factors of very different magnitudes);
#   etch         mixture_etch.csv, Scheffé quadratic mixture (no intercept) in x1, x2, x3.
# Factors are coded as rsm-lrg codes them without =LOW:HIGH (observed min and max to -1, +1;
# the mixture as given), which changes neither predictions nor their standard errors.
# For each data set: the design points and a few new settings, sides 1 and 2, P in
# {0.90, 0.99}, alpha (= 1 - confidence) in {0.05, 0.10}; the bounds are on lm's scale (log y
# for `scales`). Run: Rscript tolerance.R (writes tolerance_expected.csv).
# Needs the tolerance package (install.packages("tolerance")); without it, set TOLERANCE_SRC to
# the file R/regtol.int.R of the package's sources and the function is sourced from there.
if (requireNamespace("tolerance", quietly = TRUE)) {
  regtol <- tolerance::regtol.int
  source_of <- paste("tolerance", packageVersion("tolerance"))
} else {
  source(Sys.getenv("TOLERANCE_SRC"))
  regtol <- regtol.int
  source_of <- paste("regtol.int.R sourced from", Sys.getenv("TOLERANCE_SRC"))
}
code <- function(x) (x - (max(x) + min(x)) / 2) / ((max(x) - min(x)) / 2)
code_new <- function(v, x) (v - (max(x) + min(x)) / 2) / ((max(x) - min(x)) / 2)

rows <- list()
run <- function(set, fit, new_x, n_design) {
  for (side in c(1, 2)) for (P in c(0.90, 0.99)) for (alpha in c(0.05, 0.10)) {
    out <- regtol(fit, new.x = new_x, side = side, alpha = alpha, P = P, new = TRUE)$tol
    lo <- out[[3]]
    hi <- out[[4]]
    rows[[length(rows) + 1]] <<- data.frame(
      set = set, point = seq_len(nrow(out)), side = side, P = P, alpha = alpha,
      y_hat = sprintf("%.17g", out$y.hat), lower = sprintf("%.17g", lo), upper = sprintf("%.17g", hi))
  }
}

# heli: new settings in actual units
heli <- read.csv("heli.csv")
hx <- data.frame(A = code(heli$A), R = code(heli$R), W = code(heli$W), L = code(heli$L), y = heli$ave)
new_heli <- data.frame(A = c(12.4, 11.0, 13.9), R = c(2.5, 2.0, 2.9), W = c(1.1, 0.9, 1.3), L = c(1.6, 1.4, 2.1))
new_heli_c <- data.frame(A = code_new(new_heli$A, heli$A), R = code_new(new_heli$R, heli$R),
                         W = code_new(new_heli$W, heli$W), L = code_new(new_heli$L, heli$L))
f_heli <- lm(y ~ A + R + W + L + A:R + A:W + A:L + R:W + R:L + W:L + I(A^2) + I(R^2) + I(W^2) + I(L^2), data = hx)
run("heli", f_heli, new_heli_c, nrow(hx))

# scales: log(y), quadratic
sc <- read.csv("lm_scales.csv")
sx <- data.frame(A = code(sc$thickness_m), B = code(sc$freq_hz), C = code(sc$temp_c), y = log(sc$y))
new_sc <- data.frame(thickness_m = c(2.5e-4, 3.1e-4), freq_hz = c(2.0e6, 3.5e6), temp_c = c(60, 80))
new_sc_c <- data.frame(A = code_new(new_sc$thickness_m, sc$thickness_m), B = code_new(new_sc$freq_hz, sc$freq_hz),
                       C = code_new(new_sc$temp_c, sc$temp_c))
f_sc <- lm(y ~ A + B + C + A:B + A:C + B:C + I(A^2) + I(B^2) + I(C^2), data = sx)
run("scales", f_sc, new_sc_c, nrow(sx))

# etch: Scheffé quadratic, no intercept
etch <- read.csv("mixture_etch.csv")
ex <- data.frame(A = etch$x1, B = etch$x2, C = etch$x3, y = etch$erate)
new_etch <- data.frame(A = c(0.2, 0.5, 0.1), B = c(0.3, 0.25, 0.1), C = c(0.5, 0.25, 0.8))
f_etch <- lm(y ~ -1 + A + B + C + A:B + A:C + B:C, data = ex)
run("etch", f_etch, new_etch, nrow(ex))

res <- do.call(rbind, rows)
write.csv(res, "tolerance_expected.csv", row.names = FALSE, quote = FALSE)
cat("wrote tolerance_expected.csv with", source_of, "\n")
