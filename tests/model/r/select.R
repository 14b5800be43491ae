# Forward, backward and stepwise selection by BIC as R's step() makes it: reference for
# tests/model/choice/test_select.py. step(k = log(n)) respects marginality (an interaction enters after
# its main effects and leaves before them), which is the hierarchy rsm-lrg keeps, so on a 2FI
# model both search the same models by the same criterion (BIC up to a constant).
# Data: datasets::mtcars (mpg ~ wt, hp, qsec, disp), datasets::swiss (Fertility ~ Agriculture,
# Examination, Education, Catholic), datasets::stackloss (stack.loss ~ Air.Flow, Water.Temp,
# Acid.Conc.), and the paper's Table 4 (data/table4.csv).
# Factors coded -1..+1 from their observed minimum and maximum, as rsm-lrg codes them.
#   Rscript tests/model/r/select.R      (from the repository root or from this folder; R 4.2)
here <- if (file.exists("select.R")) "." else "tests/model/r"
root <- file.path(here, "..", "..", "..")
if (!file.exists(file.path(here, "select_mtcars.csv"))) {
  write.csv(mtcars[, c("wt", "hp", "qsec", "disp", "mpg")], file.path(here, "select_mtcars.csv"), row.names = FALSE)
  write.csv(swiss[, c("Agriculture", "Examination", "Education", "Catholic", "Fertility")],
            file.path(here, "select_swiss.csv"), row.names = FALSE)
  write.csv(stackloss, file.path(here, "select_stackloss.csv"), row.names = FALSE)
}
cases <- list(
  list(name = "mtcars", file = file.path(here, "select_mtcars.csv"), y = "mpg", x = c("wt", "hp", "qsec", "disp")),
  list(name = "swiss", file = file.path(here, "select_swiss.csv"), y = "Fertility",
       x = c("Agriculture", "Examination", "Education", "Catholic")),
  list(name = "stackloss", file = file.path(here, "select_stackloss.csv"), y = "stack.loss",
       x = c("Air.Flow", "Water.Temp", "Acid.Conc.")),
  list(name = "table4", file = file.path(root, "data", "table4.csv"), y = "tcr_c_per_min",
       x = c("thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"))
)
out <- c("dataset,direction,terms")
ours <- function(labels) if (length(labels) == 0) "" else
  paste(sort(sapply(strsplit(labels, ":"), function(p) paste(sort(p), collapse = ""))), collapse = " ")
for (cs in cases) {
  d <- read.csv(cs$file)
  L <- LETTERS[seq_along(cs$x)]
  X <- data.frame(y = d[[cs$y]])
  for (i in seq_along(cs$x)) {
    v <- d[[cs$x[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  n <- nrow(X)
  upper <- as.formula(paste("~ (", paste(L, collapse = " + "), ")^2"))
  full <- lm(as.formula(paste("y ~ (", paste(L, collapse = " + "), ")^2")), data = X)
  null <- lm(y ~ 1, data = X)
  fw <- step(null, scope = list(lower = ~ 1, upper = upper), direction = "forward", k = log(n), trace = 0)
  bw <- step(full, scope = list(lower = ~ 1, upper = upper), direction = "backward", k = log(n), trace = 0)
  sw <- step(null, scope = list(lower = ~ 1, upper = upper), direction = "both", k = log(n), trace = 0)
  for (r in list(c("forward", ours(attr(terms(fw), "term.labels"))),
                 c("backward", ours(attr(terms(bw), "term.labels"))),
                 c("stepwise", ours(attr(terms(sw), "term.labels")))))
    out <- c(out, paste(cs$name, r[1], r[2], sep = ","))
}
writeLines(out, file.path(here, "select_step_expected.csv"))
