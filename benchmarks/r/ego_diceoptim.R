# R DiceOptim::EGO.nsteps from given initial designs: the reference of benchmarks/bench_ego.py.
#
# Usage: Rscript ego_diceoptim.R PROBLEM INITIAL.csv NSTEPS OUT.csv [FIFO_IN FIFO_OUT]
#
# INITIAL.csv: columns seed, x1..xk (actual units), y: one initial design per seed (the same
# Latin hypercubes rsm-lrg's loop starts from). For each seed: km(~1, covtype = "matern5_2",
# no nugget) on the initial design, then EGO.nsteps(model, fun, NSTEPS, lower, upper) with
# DiceOptim's defaults (EI maximised by rgenoud; the covariance parameters re-estimated at every
# step). OUT.csv: seed, evaluation (1-based, the initial runs first), y. PROBLEM: branin,
# hartmann6 (functions below, as in bench_ego.py) or surrogate, whose values come from a
# Python process over two FIFOs (a line "x1,...,xk" written to FIFO_IN, the value read back
# from FIFO_OUT). A seed whose EGO stops with an error (a singular covariance matrix) keeps
# the evaluations made before it; the script prints how many. R's random numbers (km's start,
# genoud's population) are seeded by set.seed(seed + EGO_R_SEED_OFFSET), the environment
# variable defaulting to 0: another offset runs the same reference with other draws, which
# measures how much its median owes to them.
suppressPackageStartupMessages({library(DiceKriging); library(DiceOptim)})
args <- commandArgs(trailingOnly = TRUE)
problem <- args[1]; init <- read.csv(args[2]); nsteps <- as.integer(args[3]); out_path <- args[4]

branin <- function(x) {
  x1 <- x[1]; x2 <- x[2]
  (x2 - 5.1 / (4 * pi^2) * x1^2 + 5 / pi * x1 - 6)^2 + 10 * (1 - 1 / (8 * pi)) * cos(x1) + 10
}
A <- matrix(c(10, 3, 17, 3.5, 1.7, 8, 0.05, 10, 17, 0.1, 8, 14, 3, 3.5, 1.7, 10, 17, 8,
              17, 8, 0.05, 10, 0.1, 14), 4, 6, byrow = TRUE)
P <- 1e-4 * matrix(c(1312, 1696, 5569, 124, 8283, 5886, 2329, 4135, 8307, 3736, 1004, 9991,
                     2348, 1451, 3522, 2883, 3047, 6650, 4047, 8828, 8732, 5743, 1091, 381), 4, 6, byrow = TRUE)
alpha <- c(1.0, 1.2, 3.0, 3.2)
hartmann6 <- function(x) -sum(alpha * exp(-rowSums(A * (matrix(x, 4, 6, byrow = TRUE) - P)^2)))

if (problem == "surrogate") {
  fifo_in <- args[5]; fifo_out <- args[6]
  fun <- function(x) {
    con <- file(fifo_in, "w"); writeLines(paste(format(x, digits = 17), collapse = ","), con); close(con)
    con <- file(fifo_out, "r"); v <- as.numeric(readLines(con, n = 1)); close(con)
    v
  }
} else {
  fun <- get(problem)
}
xcols <- grep("^x", names(init), value = TRUE)
bounds <- read.csv(sub("\\.csv$", "_bounds.csv", args[2]))
lower <- as.numeric(bounds$low); upper <- as.numeric(bounds$high)
r_offset <- as.integer(Sys.getenv("EGO_R_SEED_OFFSET", "0"))
rows <- list()
for (s in unique(init$seed)) {
  d <- init[init$seed == s, ]
  X <- d[, xcols, drop = FALSE]; y <- d$y
  set.seed(s + r_offset)
  res <- tryCatch({
    m <- km(~1, design = X, response = y, covtype = "matern5_2", control = list(trace = FALSE))
    e <- EGO.nsteps(m, fun, nsteps, lower, upper, kmcontrol = list(control = list(trace = FALSE)))
    c(y, e$value)
  }, error = function(err) {
    message(sprintf("seed %d: EGO stopped: %s", s, conditionMessage(err)))
    y
  })
  rows[[length(rows) + 1]] <- data.frame(seed = s, evaluation = seq_along(res), y = res)
  cat(sprintf("seed %d: %d evaluations, best %.6g\n", s, length(res), min(res)))
}
write.csv(do.call(rbind, rows), out_path, row.names = FALSE)
