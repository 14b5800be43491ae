# Generalised linear models as R's glm computes them: reference for tests/model/pipelines/test_glm_r.py.
#
# Published data sets (none used to tune the Python code):
#   glm_mtcars.csv     datasets::mtcars (Henderson & Velleman 1981): am (0/1) ~ hp + wt (logit only: the
#                      probit and cloglog fits reach fitted probabilities of 0 or 1 to machine precision)
#   glm_birthwt.csv    MASS::birthwt (Hosmer & Lemeshow 1989): low (0/1) ~ quadratic(age, lwt)
#   glm_budworm.csv    Venables & Ripley, MASS 4th ed. (2002) sec. 7.2 (Collett 1991): numdead of
#                      20 budworms ~ ldose * sex (successes and trials; sex categoric)
#   glm_warpbreaks.csv datasets::warpbreaks (Tippett 1950): breaks (count) ~ wool * tension
#   glm_biochem.csv    pscl::bioChemists (Long 1990): art (count) ~ quadratic(ment, phd)
# Numeric factors are coded -1..+1 from their observed minimum and maximum, categoric factors
# are sum-to-zero (contr.sum) with the levels in the order given, as rsm-lrg codes them.
# glm is run to the maximum-likelihood estimate itself (epsilon 1e-14, then restarted from its
# own estimate until the coefficients repeat to 1e-13), not to its default deviance tolerance of
# 1e-8, so that the standard errors are those at the estimate. The analysis of deviance: drop1(fit, scope = every term,
# test = "LRT") (each term dropped from the full model) and anova(fit, test = "LRT")
# (sequential). Predictions: predict(type = "link", se.fit = TRUE), the 95 % interval
# linkinv(eta -/+ qnorm(0.975) se), and predict(type = "response", se.fit = TRUE).
#   Rscript tests/model/r/glm.R      (from the repository root or from this folder; R 4.2)
here <- if (file.exists("glm.R")) "." else "tests/model/r"
options(contrasts = c("contr.sum", "contr.poly"))
g <- function(x) sprintf("%.17g", x)
q <- function(x) paste0("\"", x, "\"")

# the data files, written once from the R packages and the book
if (!file.exists(file.path(here, "glm_mtcars.csv"))) {
  write.csv(data.frame(hp = mtcars$hp, wt = mtcars$wt, am = mtcars$am), file.path(here, "glm_mtcars.csv"),
            row.names = FALSE)
  bw <- MASS::birthwt
  write.csv(data.frame(age = bw$age, lwt = bw$lwt, low = bw$low), file.path(here, "glm_birthwt.csv"),
            row.names = FALSE)
  write.csv(data.frame(ldose = rep(0:5, 2), sex = rep(c("M", "F"), each = 6),
                       numdead = c(1, 4, 9, 13, 18, 20, 0, 2, 6, 10, 12, 16), n = 20),
            file.path(here, "glm_budworm.csv"), row.names = FALSE)
  write.csv(data.frame(wool = as.character(warpbreaks$wool), tension = as.character(warpbreaks$tension),
                       breaks = warpbreaks$breaks), file.path(here, "glm_warpbreaks.csv"), row.names = FALSE)
  bc <- pscl::bioChemists
  write.csv(data.frame(ment = bc$ment, phd = bc$phd, art = bc$art), file.path(here, "glm_biochem.csv"),
            row.names = FALSE)
}

cases <- list(
  list(name = "mtcars", y = "am", num = c("hp", "wt"), cat = list(), trials = NULL, model = "linear",
       fams = list(c("binomial", "logit")),
       new = data.frame(hp = c(100, 150, 250), wt = c(2.5, 3.2, 3.6))),
  list(name = "birthwt", y = "low", num = c("age", "lwt"), cat = list(), trials = NULL, model = "quadratic",
       fams = list(c("binomial", "logit"), c("binomial", "probit"), c("binomial", "cloglog")),
       new = data.frame(age = c(18, 25, 35), lwt = c(100, 130, 200))),
  list(name = "budworm", y = "numdead", num = c("ldose"), cat = list(sex = c("F", "M")), trials = "n",
       model = "2fi", fams = list(c("binomial", "logit"), c("binomial", "probit"), c("binomial", "cloglog")),
       new = data.frame(ldose = c(1.5, 3, 4.5), sex = c("F", "M", "F"))),
  list(name = "warpbreaks", y = "breaks", num = c(), cat = list(wool = c("A", "B"), tension = c("L", "M", "H")),
       trials = NULL, model = "2fi", fams = list(c("poisson", "log")),
       new = data.frame(wool = c("A", "B", "B"), tension = c("M", "L", "H"))),
  list(name = "biochem", y = "art", num = c("ment", "phd"), cat = list(), trials = NULL, model = "quadratic",
       fams = list(c("poisson", "log")),
       new = data.frame(ment = c(2, 10, 40), phd = c(1.5, 3, 4.2)))
)

coef_out <- c("dataset,family,link,column,estimate,std_error,z,p")
drop_out <- c("dataset,family,link,source,df,chi_square,p,resid_deviance")
seq_out <- c("dataset,family,link,source,df,chi_square,p,resid_df,resid_deviance")
stat_out <- c("dataset,family,link,stat,value")
pred_out <- c("dataset,family,link,row,link_fit,link_se,fit,se_fit,ci_low,ci_high")
for (cs in cases) {
  d <- read.csv(file.path(here, paste0("glm_", cs$name, ".csv")), stringsAsFactors = FALSE)
  nn <- length(cs$num); nc <- length(cs$cat)
  L <- LETTERS[seq_len(nn + nc)]
  X <- data.frame(row = seq_len(nrow(d)))
  nw <- data.frame(row = seq_len(nrow(cs$new)))
  for (i in seq_len(nn)) {
    v <- d[[cs$num[i]]]; lo <- min(v); hi <- max(v)
    X[[L[i]]] <- (v - (lo + hi) / 2) / ((hi - lo) / 2)
    nw[[L[i]]] <- (cs$new[[cs$num[i]]] - (lo + hi) / 2) / ((hi - lo) / 2)
  }
  for (j in seq_len(nc)) {
    col <- names(cs$cat)[j]
    X[[L[nn + j]]] <- factor(d[[col]], levels = cs$cat[[j]])
    nw[[L[nn + j]]] <- factor(cs$new[[col]], levels = cs$cat[[j]])
  }
  pairs <- if (length(L) > 1) paste(combn(L, 2, paste, collapse = ":"), collapse = " + ") else NULL
  squares <- if (nn > 0) paste0("I(", L[seq_len(nn)], "^2)", collapse = " + ") else NULL
  rhs <- paste(c(paste(L, collapse = " + "), if (cs$model != "linear") pairs,
                 if (cs$model == "quadratic") squares), collapse = " + ")
  if (is.null(cs$trials)) {
    X$y <- d[[cs$y]]
    f <- as.formula(paste("y ~", rhs))
  } else {
    X$s <- d[[cs$y]]; X$f <- d[[cs$trials]] - d[[cs$y]]
    f <- as.formula(paste("cbind(s, f) ~", rhs))
  }
  f <- terms(f, keep.order = TRUE)  # Design-Expert's order (A, B, AB, A^2, B^2) for the sequential table
  for (fl in cs$fams) {
    fam <- get(fl[1])(link = fl[2])
    ctl <- glm.control(epsilon = 1e-14, maxit = 200)
    m <- glm(f, family = fam, data = X, control = ctl)
    for (k in 1:200) {  # restarted from its own estimate until the coefficients repeat (Fisher scoring
      b <- coef(m)      # converges linearly for probit and cloglog: epsilon alone leaves ~1e-8)
      m <- glm(f, family = fam, data = X, start = b, control = glm.control(epsilon = 1e-12, maxit = 200))
      if (max(abs(coef(m) - b) / (1 + abs(b))) < 1e-13) break
    }
    stopifnot(m$converged, all(fitted(m) > 1e-12), fl[1] != "binomial" || all(fitted(m) < 1 - 1e-12))
    tag <- paste(cs$name, fl[1], fl[2], sep = ",")
    co <- summary(m)$coefficients
    for (t in rownames(co)) coef_out <- c(coef_out, paste(tag, q(t), g(co[t, 1]), g(co[t, 2]), g(co[t, 3]),
                                                          g(co[t, 4]), sep = ","))
    labs <- attr(terms(m), "term.labels")
    dr <- drop1(m, scope = labs, test = "LRT")
    for (t in labs) drop_out <- c(drop_out, paste(tag, q(t), dr[t, "Df"], g(dr[t, "LRT"]), g(dr[t, "Pr(>Chi)"]),
                                                  g(dr[t, "Deviance"]), sep = ","))
    an <- anova(m, test = "LRT")
    for (t in labs) seq_out <- c(seq_out, paste(tag, q(t), an[t, "Df"], g(an[t, "Deviance"]), g(an[t, "Pr(>Chi)"]),
                                                an[t, "Resid. Df"], g(an[t, "Resid. Dev"]), sep = ","))
    st <- c(deviance = deviance(m), df_resid = df.residual(m), null_deviance = m$null.deviance,
            df_null = m$df.null, pearson_chi2 = sum(residuals(m, "pearson")^2),
            log_likelihood = as.numeric(logLik(m)), aic = AIC(m), bic = BIC(m))
    for (k in names(st)) stat_out <- c(stat_out, paste(tag, k, g(st[[k]]), sep = ","))
    pl <- predict(m, newdata = nw, type = "link", se.fit = TRUE)
    pr <- predict(m, newdata = nw, type = "response", se.fit = TRUE)
    z <- qnorm(0.975)
    lo <- fam$linkinv(pl$fit - z * pl$se.fit); hi <- fam$linkinv(pl$fit + z * pl$se.fit)
    for (i in seq_len(nrow(nw))) pred_out <- c(pred_out, paste(tag, i, g(pl$fit[i]), g(pl$se.fit[i]), g(pr$fit[i]),
                                                               g(pr$se.fit[i]), g(lo[i]), g(hi[i]), sep = ","))
  }
}
writeLines(coef_out, file.path(here, "glm_coef_expected.csv"))
writeLines(drop_out, file.path(here, "glm_drop1_expected.csv"))
writeLines(seq_out, file.path(here, "glm_anova_expected.csv"))
writeLines(stat_out, file.path(here, "glm_stats_expected.csv"))
writeLines(pred_out, file.path(here, "glm_pred_expected.csv"))
