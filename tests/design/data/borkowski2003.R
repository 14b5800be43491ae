# Borkowski (2003) small exact D-, A-, G- and IV-optimal designs for the full quadratic model
# on the cube [-1, 1]^k, k = 2 (N = 6..12) and k = 3 (N = 10..16), as catalogued in the R
# package VdgRsm 1.5 (function Borkowski2003, file R/VdgRsm.R; CRAN mirror github:cran/VdgRsm,
# commit 22eefc9). Source: Borkowski, J. J. (2003). Using a genetic algorithm to generate
# small exact response surface designs. Journal of Probability and Statistical Science
# 1(1), 65-88.
#
# Regenerate borkowski2003.csv (run from this folder, with VdgRsm.R from that package here):
#   Rscript borkowski2003.R
# Cases VdgRsm leaves out are simply absent (A: k = 2, N = 10, 11; k = 3, N = 14, 15).
src <- readLines("VdgRsm.R")
eval(parse(text = src))  # Borkowski2003() calls the package's gen.CCD for some k = 3 designs
out <- NULL
for (cr in c("D", "A", "G", "IV")) for (k in 2:3) for (N in 1:40) {
  d <- tryCatch(suppressWarnings(Borkowski2003(cr, k, N)), error = function(e) NULL)
  if (is.data.frame(d) && nrow(d) == N) {
    if (k == 2) d$X3 <- NA
    out <- rbind(out, data.frame(criterion = cr, k = k, N = N, run = seq_len(N),
                                 x1 = d$X1, x2 = d$X2, x3 = d$X3))
  }
}
write.csv(out, "borkowski2003.csv", row.names = FALSE, na = "")
