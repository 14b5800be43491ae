# Forward, backward and stepwise selection of a GLM by BIC as R's step() makes it: reference for
# tests/model/pipelines/test_glm_select.py. step(k = log(n)) on a glm uses deviance + k * edf, which differs
# from -2 logLik + p log(n) by a constant, and keeps marginality (the hierarchy rsm-lrg keeps).
# Data: MASS::birthwt (low ~ age, lwt, ptl, ftv; binomial logit), pscl::bioChemists (art ~ ment,
# phd, kid5; poisson log), datasets::warpbreaks (breaks ~ wool * tension; poisson log, categoric).
# Numeric factors coded -1..+1 from their observed minimum and maximum; contr.sum.
#   Rscript tests/model/r/glm_select.R      (from the repository root or from this folder; R 4.2)
here <- if (file.exists("glm_select.R")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
if (!file.exists(file.path(here, "glm_select_birthwt.csv"))) {
  bw <- MASS::birthwt
  write.csv(bw[, c("age", "lwt", "ptl", "ftv", "low")], file.path(here, "glm_select_birthwt.csv"), row.names = FALSE)
  bc <- pscl::bioChemists
  write.csv(data.frame(ment = bc$ment, phd = bc$phd, kid5 = bc$kid5, art = bc$art),
            file.path(here, "glm_select_biochem.csv"), row.names = FALSE)
}
cases <- list(
  list(name = "birthwt", file = "glm_select_birthwt.csv", y = "low", num = c("age", "lwt", "ptl", "ftv"),
       cat = list(), fam = binomial()),
  list(name = "biochem", file = "glm_select_biochem.csv", y = "art", num = c("ment", "phd", "kid5"), cat = list(),
       fam = poisson()),
  list(name = "warpbreaks", file = "glm_warpbreaks.csv", y = "breaks", num = c(),
       cat = list(wool = c("A", "B"), tension = c("L", "M", "H")), fam = poisson())
)
ours <- function(labels) if (length(labels) == 0) "" else
  paste(sort(sapply(strsplit(labels, ":"), function(p) paste(sort(p), collapse = ""))), collapse = " ")
out <- c("dataset,direction,terms")
for (cs in cases) {
  d <- read.csv(file.path(here, cs$file), stringsAsFactors = FALSE)
  nn <- length(cs$num); L <- LETTERS[seq_len(nn + length(cs$cat))]
  X <- data.frame(y = d[[cs$y]])
  for (i in seq_len(nn)) {
    v <- d[[cs$num[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  for (j in seq_along(cs$cat)) X[[L[nn + j]]] <- factor(d[[names(cs$cat)[j]]], levels = cs$cat[[j]])
  n <- nrow(X)
  upper <- as.formula(paste("~ (", paste(L, collapse = " + "), ")^2"))
  ctl <- glm.control(epsilon = 1e-12, maxit = 100)
  full <- glm(as.formula(paste("y ~ (", paste(L, collapse = " + "), ")^2")), family = cs$fam, data = X, control = ctl)
  null <- glm(y ~ 1, family = cs$fam, data = X, control = ctl)
  sc <- list(lower = ~ 1, upper = upper)
  fw <- step(null, scope = sc, direction = "forward", k = log(n), trace = 0)
  bw <- step(full, scope = sc, direction = "backward", k = log(n), trace = 0)
  sw <- step(null, scope = sc, direction = "both", k = log(n), trace = 0)
  for (r in list(c("forward", ours(attr(terms(fw), "term.labels"))),
                 c("backward", ours(attr(terms(bw), "term.labels"))),
                 c("stepwise", ours(attr(terms(sw), "term.labels")))))
    out <- c(out, paste(cs$name, r[1], r[2], sep = ","))
}
writeLines(out, file.path(here, "glm_select_expected.csv"))
