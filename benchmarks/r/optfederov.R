# D-optimal exact design for the full quadratic model in k factors, N runs, by AlgDesign's
# optFederov on the 3^k grid (the classic candidate set), written as a CSV of coded runs.
# Usage: Rscript optfederov.R K N SEED OUT.csv   (benchmarks/bench_design.py runs it)
args <- commandArgs(trailingOnly = TRUE)
k <- as.integer(args[1]); n <- as.integer(args[2]); seed <- as.integer(args[3]); out <- args[4]
suppressMessages(library(AlgDesign))
set.seed(seed)
cand <- gen.factorial(levels = 3, nVars = k, center = TRUE, varNames = paste0("x", seq_len(k)))
res <- optFederov(~quad(.), data = cand, nTrials = n, criterion = "D")
write.csv(res$design, out, row.names = FALSE)
