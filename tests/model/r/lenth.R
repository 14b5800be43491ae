# Lenth's (1989) PSE, ME and SME from Lenth's own R package unrepx 1.0-2 (github:cran/unrepx,
# files R/scalests.R and R/examples.R), for the published effect examples it ships
# (Box, Hunter & Hunter 2005: pdEff, bikeEff, shnkEff, shnkDisp; simulated: viseEff).
# Run: Rscript lenth.R /path/to/unrepx/R > lenth_expected.csv
args <- commandArgs(trailingOnly = TRUE)
source(file.path(args[1], "scalests.R"))
source(file.path(args[1], "examples.R"))
# Montgomery (2013), Design and Analysis of Experiments 8th ed., Example 6.2 (filtration rate,
# unreplicated 2^4): the published effects A B AB C AC BC ABC D AD BD ABD CD ACD BCD ABCD
montgomery62 <- c(21.625, 3.125, 0.125, 9.875, -18.125, 2.375, 1.875, 14.625, 16.625,
                  -0.375, 4.125, -1.125, -1.625, -2.625, 1.375)
cat("example,m,effects,pse,me,sme\n")
for (nm in c("montgomery62", "pdEff", "bikeEff", "viseEff", "shnkEff", "shnkDisp")) {
  e <- get(nm)
  m <- length(e)
  pse <- unname(PSE(e, method = "Lenth"))
  d <- m / 3
  me <- qt(0.975, d) * pse
  sme <- qt((1 + 0.95^(1 / m)) / 2, d) * pse
  cat(sprintf("%s,%d,%s,%.17g,%.17g,%.17g\n", nm, m, paste(sprintf("%.17g", as.numeric(e)), collapse = " "), pse, me, sme))
}
