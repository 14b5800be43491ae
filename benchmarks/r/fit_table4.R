# The R side of benchmarks/bench_cli.py: what `rsm-lrg fit data/table4.csv --response
# tcr_c_per_min` does, with R's rsm package (Lenth): read the CSV, code the four factors on
# the Table 3 levels (x = (actual - centre) / half-range), fit the full second-order model and
# print summary() (coefficients, ANOVA with lack of fit and pure error, canonical analysis).
#
#   Rscript benchmarks/r/fit_table4.R [data/table4.csv]
args <- commandArgs(trailingOnly = TRUE)
path <- if (length(args) >= 1) args[1] else "data/table4.csv"
suppressPackageStartupMessages(library(rsm))
d <- read.csv(path)
cd <- coded.data(d,
                 x1 ~ (thickness_m - 0.0003) / 0.0002,
                 x2 ~ (stroke_m - 0.05) / 0.01,
                 x3 ~ (velocity_m_s - 0.5) / 0.1,
                 x4 ~ (acceleration_m_s2 - 30) / 10)
m <- rsm(tcr_c_per_min ~ SO(x1, x2, x3, x4), data = cd)
print(summary(m))
