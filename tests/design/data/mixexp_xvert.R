# Extreme vertices of the McLean & Anderson (1966) flare mixture from R mixexp's Xvert,
# the reference for tests/design/test_design_mixture.py (mixexp_xvert.csv, mixexp_sld.csv).
# mixexp (github cran/mixexp) was installed into /tmp/rlib with its 'daewr' dependency
# removed from DESCRIPTION and NAMESPACE (daewr supplies data sets only, not Xvert/SLD/SCD):
#   R CMD INSTALL -l /tmp/rlib <mixexp source>
# Run: Rscript tests/design/data/mixexp_xvert.R  (writes the CSVs beside this script)
# Xvert computes in single precision (the Fortran routine 'cnvrt'), so its vertices agree
# with an exact enumeration only to about 1e-7.
.libPaths(c("/tmp/rlib", .libPaths()))
library(mixexp)
here <- dirname(sub("--file=", "", grep("--file=", commandArgs(FALSE), value = TRUE)))
# x1 magnesium 0.40-0.60, x2 sodium nitrate 0.10-0.50, x3 strontium nitrate 0.10-0.50,
# x4 binder 0.03-0.08 (McLean & Anderson 1966, Technometrics 8, 447-454)
v <- Xvert(nfac = 4, lc = c(0.40, 0.10, 0.10, 0.03), uc = c(0.60, 0.50, 0.50, 0.08),
           ndm = 0, plot = FALSE, pseudo = FALSE)
write.csv(v, file.path(here, "mixexp_xvert.csv"), row.names = FALSE)
# with centroids up to dimension 2 (edges, 2-faces) and the overall centroid
vc <- Xvert(nfac = 4, lc = c(0.40, 0.10, 0.10, 0.03), uc = c(0.60, 0.50, 0.50, 0.08),
            ndm = 2, plot = FALSE, pseudo = FALSE)
write.csv(vc, file.path(here, "mixexp_xvert_centroids.csv"), row.names = FALSE)
# simplex lattice {4, 3} and simplex centroid, q = 4
write.csv(SLD(fac = 4, lev = 3), file.path(here, "mixexp_sld.csv"), row.names = FALSE)
write.csv(SCD(fac = 4), file.path(here, "mixexp_scd.csv"), row.names = FALSE)
