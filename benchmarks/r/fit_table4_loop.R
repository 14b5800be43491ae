# The R side of `benchmarks/bench_cli.py --in-process`: rsm() + print(summary()) on Table 4,
# as fit_table4.R does once, here repeated N times inside one R process (after 5 warm-up
# fits) and timed by system.time: prints the CPU milliseconds (user + system) per fit.
#
#   Rscript benchmarks/r/fit_table4_loop.R [data/table4.csv] [N]
args <- commandArgs(trailingOnly = TRUE)
path <- if (length(args) >= 1) args[1] else "data/table4.csv"
n <- if (length(args) >= 2) as.integer(args[2]) else 50L
suppressPackageStartupMessages(library(rsm))
d <- read.csv(path)
once <- function() {
  cd <- coded.data(d,
                   x1 ~ (thickness_m - 0.0003) / 0.0002,
                   x2 ~ (stroke_m - 0.05) / 0.01,
                   x3 ~ (velocity_m_s - 0.5) / 0.1,
                   x4 ~ (acceleration_m_s2 - 30) / 10)
  m <- rsm(tcr_c_per_min ~ SO(x1, x2, x3, x4), data = cd)
  invisible(capture.output(print(summary(m))))
}
for (i in 1:5) once()
t <- system.time(for (i in seq_len(n)) once())
cat(sprintf("%.6f\n", (t[["user.self"]] + t[["sys.self"]]) * 1000 / n))
