# D-optimal exact mixture designs by AlgDesign's optFederov (Fedorov exchange) on the same
# candidate sets as rsm_lrg (mixture_cand_<case>.csv, written by make_mixture_candidates.py;
# L-pseudo components A, B, C(, D), process factor last), for
# tests/design/test_design_mixture_optimal.py. Run: R_LIBS=/tmp/rlib Rscript mixture_optimal.R
# Writes mixture_optimal_expected.csv: per case the best D = det(X'X)^(1/p) / N over 20 seeds
# (nRepeats = 20 each) and the rows chosen.
suppressMessages(library(AlgDesign))
cases <- list(
  quad3 = list(f = ~ -1 + A + B + C + A:B + A:C + B:C, n = 10),
  flare4 = list(f = ~ -1 + A + B + C + D + A:B + A:C + A:D + B:C + B:D + C:D + A:B:C + A:B:D + A:C:D + B:C:D,
                n = 18),
  cubic3 = list(f = ~ -1 + A + B + C + A:B + A:C + B:C + A:B:C + I(A * B * (A - B)) + I(A * C * (A - C)) +
                  I(B * C * (B - C)), n = 12),
  proc3 = list(f = ~ -1 + (A + B + C + A:B + A:C + B:C) + (A + B + C + A:B + A:C + B:C):D, n = 16)
)
out <- list()
for (nm in names(cases)) {
  cand <- read.csv(paste0("mixture_cand_", nm, ".csv"))
  cs <- cases[[nm]]
  best <- -Inf; rows <- NULL
  for (seed in 1:20) {
    set.seed(seed)
    res <- optFederov(cs$f, data = cand, nTrials = cs$n, criterion = "D", nRepeats = 20)
    X <- model.matrix(cs$f, res$design)
    d <- exp(determinant(crossprod(X))$modulus[1] / ncol(X)) / cs$n
    if (d > best) { best <- d; rows <- res$rows }
  }
  out[[nm]] <- data.frame(case = nm, runs = cs$n, p = ncol(X), d = sprintf("%.17g", best),
                          rows = paste(rows, collapse = " "))
}
write.csv(do.call(rbind, out), "mixture_optimal_expected.csv", row.names = FALSE, quote = FALSE)
