# D-optimal blocked mixture designs by R AlgDesign's optBlock (blocks as fixed effects) on the
# same candidate sets as rsm_lrg (mixture_cand_<case>.csv, written by
# make_mixture_candidates.py: L-pseudo components A, B, C(, D), the process factor last), for
# tests/design/test_design_mixture_blocks.py. AlgDesign built from github cran/AlgDesign
# (1.2.1) with R CMD INSTALL -l /tmp/rlib; run from this folder:
#   R_LIBS=/tmp/rlib Rscript mixture_blocks.R
# optBlock draws its runs from withinData without replacement: the candidates are given once
# per block (a point may then recur, as an exchange over the candidate set allows). The model
# is the Scheffe model written with an intercept (one linear blending term dropped: the same
# column space), since optBlock removes the constant and centres every row in its block:
# its D = det(X_c'X_c / N)^(1/k), k the columns without the constant. Best of 10 seeds x
# nRepeats 50. AlgDesign 1.2.1.2 keeps a repeat only when its log det beats 0 (OptBlock.c:
# logDbest starts at 0), so a design whose det(M) < 1 (pseudo components in 0..1, products
# smaller still) is never improved on ("No improvement over initial random design"): the
# components are therefore given to optBlock multiplied by 10 (the D-optimal design is the same
# under any scaling of the columns) and D is recomputed on the unscaled columns.
# Writes mixture_blocks_expected.csv: case, runs, k, the block sizes, optBlock's D on the
# unscaled columns, and the design as candidate rows (1-based) and their blocks.
suppressMessages(library(AlgDesign))
cases <- list(
  quad3 = list(f = ~ A + B + A:B + A:C + B:C, sizes = c(7, 7)),
  proc3 = list(f = ~ (A + B + A:B + A:C + B:C) * D, sizes = c(8, 8, 8)),
  flare4 = list(f = ~ A + B + C + A:B + A:C + A:D + B:C + B:D + C:D + A:B:C + A:B:D + A:C:D + B:C:D,
                sizes = c(7, 7, 7))
)
out <- list()
for (nm in names(cases)) {
  cand <- read.csv(paste0("mixture_cand_", nm, ".csv"))
  cs <- cases[[nm]]
  m <- nrow(cand); nb <- length(cs$sizes)
  comp <- setdiff(names(cand), "D")
  if (nm == "flare4") comp <- names(cand)  # four components, no process factor
  scaled <- cand
  scaled[comp] <- 10 * cand[comp]
  within <- scaled[rep(seq_len(m), nb), , drop = FALSE]
  rownames(within) <- seq_len(nrow(within))
  best <- -Inf
  for (seed in 1:10) {
    set.seed(seed)
    res <- optBlock(cs$f, withinData = within, blocksizes = cs$sizes, nRepeats = 50)
    rr <- (res$rows - 1) %% m + 1
    blk <- rep(seq_len(nb), cs$sizes)
    X <- model.matrix(cs$f, cand[rr, , drop = FALSE])[, -1, drop = FALSE]  # unscaled, no constant
    Xc <- X - apply(X, 2, function(v) ave(v, blk))
    d <- exp(determinant(crossprod(Xc) / nrow(X))$modulus[1] / ncol(X))
    if (d > best) { best <- d; rows <- rr; k <- ncol(X) }
  }
  out[[nm]] <- data.frame(case = nm, runs = sum(cs$sizes), k = k, sizes = paste(cs$sizes, collapse = " "),
                          d = sprintf("%.17g", best), rows = paste(rows, collapse = " "),
                          blocks = paste(rep(seq_len(nb), cs$sizes), collapse = " "))
}
write.csv(do.call(rbind, out), "mixture_blocks_expected.csv", row.names = FALSE, quote = FALSE)
