# R rsm's Box-Behnken design (bbd), written as a CSV: the anchor of `design box-behnken`.
# Usage: Rscript bbd.R K N0 OUT.csv   (benchmarks/bench_design.py runs it)
args <- commandArgs(trailingOnly = TRUE)
k <- as.integer(args[1]); n0 <- as.integer(args[2]); out <- args[3]
suppressMessages(library(rsm))
d <- bbd(k, n0 = n0, block = FALSE, randomize = FALSE)
write.csv(as.data.frame(d), out, row.names = FALSE)
