# ln s of the replicated settings of dispersion_cure.csv (a data set made for this test: a
# 3x3 grid in temp_c 150..190 and time_min 10..30, seven settings run 4 times, one 3 times, one
# once, plus one off-grid run; normal noise whose SD depends on the settings, seed 20261128),
# fitted by lm() on the table of settings: the independent route of tests/model/test_dispersion.py.
# Run: Rscript dispersion.R  (writes dispersion_expected.csv)
d <- read.csv("dispersion_cure.csv")
key <- paste(d$temp_c, d$time_min)
m <- tapply(d$yield_pct, key, length)
s <- tapply(d$yield_pct, key, sd)
t <- tapply(d$temp_c, key, function(v) v[1])
u <- tapply(d$time_min, key, function(v) v[1])
agg <- data.frame(temp_c = t, time_min = u, runs = m, s = s)
agg <- agg[agg$runs >= 2, ]
agg$A <- (agg$temp_c - 170) / 20       # coded as the mean's fit codes them (observed range)
agg$B <- (agg$time_min - 20) / 10
agg$AB <- agg$A * agg$B                 # a numeric column, so drop1() gives every partial SS
out <- NULL
for (model in c("linear", "2fi")) {
  f <- if (model == "linear") lm(log(s) ~ A + B, data = agg) else lm(log(s) ~ A + B + AB, data = agg)
  co <- summary(f)$coefficients
  nm <- sub("\\(Intercept\\)", "Intercept", rownames(co))
  out <- rbind(out, data.frame(model = model, what = "coef", name = nm, value = co[, 1]),
               data.frame(model = model, what = "se", name = nm, value = co[, 2]))
  a <- drop1(f, test = "F")  # partial (type III) sums of squares: the setting (190, 30) is missing
  a <- a[-1, ]
  out <- rbind(out, data.frame(model = model, what = "ss", name = rownames(a), value = a[, "Sum of Sq"]),
               data.frame(model = model, what = "ss", name = "Residuals", value = deviance(f)),
               data.frame(model = model, what = "r2", name = "r2", value = summary(f)$r.squared),
               data.frame(model = model, what = "n", name = "settings", value = nrow(agg)))
}
write.csv(out, "dispersion_expected.csv", row.names = FALSE)
