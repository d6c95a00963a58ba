# Reference values for dtlab's mixed models (tests/analysis/stats/test_lmm*.cpp).
# Makes the datasets (CSV, committed beside this script), fits each case with
# lme4 / lmerTest / pbkrtest / emmeans / afex exactly as the case's "r_call"
# says, and writes lmm_reference.json. Run from this folder:
#   Rscript make_lmm_reference.R > make_lmm_reference.Rout 2>&1
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, pbkrtest 0.5.2, emmeans 1.8.4-1,
# afex 1.2-1, nloptr 2.0.3 (NLopt 2.7.1, Debian libnlopt0).
suppressMessages({library(lmerTest); library(emmeans); library(jsonlite); library(afex)})
options(contrasts = c("contr.sum", "contr.poly"))
Sys.setlocale("LC_COLLATE", "C")

# ---- datasets -------------------------------------------------------------
write_data <- function(d, file) { write.csv(d, file, row.names = FALSE, quote = FALSE); file }
fmt17 <- function(x) sprintf("%.17g", x)

make_trials <- function(seed, ns, within, trials, sd_s = 0.3, sd_slope = 0.1, sd_e = 0.4, items = 8,
                        effects = NULL, between = NULL) {
  set.seed(seed)
  grid <- expand.grid(c(list(trial = seq_len(trials)), rev(within), list(s = sprintf("s%02d", seq_len(ns)))),
                      stringsAsFactors = FALSE)
  grid <- grid[, c("s", names(within), "trial")]
  si <- as.integer(factor(grid$s))
  u <- rnorm(ns, 0, sd_s)
  eta <- 1 + u[si]
  for (f in names(within)) {
    lv <- within[[f]]; k <- match(grid[[f]], lv)
    eff <- if (!is.null(effects[[f]])) effects[[f]] else seq(0, 0.3, length.out = length(lv))
    slope <- rnorm(ns, 0, sd_slope)
    eta <- eta + eff[k] + slope[si] * (k - 1)
  }
  if (!is.null(between)) {
    g <- rep(between$levels, times = between$sizes)
    grid[[between$name]] <- g[si]
    eta <- eta + between$effect[match(grid[[between$name]], between$levels)]
  }
  grid$item <- sprintf("i%d", sample(seq_len(items), nrow(grid), replace = TRUE))
  w <- rnorm(items, 0, 0.15)
  eta <- eta + w[as.integer(sub("i", "", grid$item))]
  grid$time <- round(exp(eta + rnorm(nrow(grid), 0, sd_e)), 6)
  grid
}

d1 <- make_trials(101, 24, list(A = c("a1", "a2"), B = c("b1", "b2")), 8)
set.seed(301)                                  # a 0/1 outcome beside the time
u1 <- rnorm(24, 0, 0.6)
d1$correct <- rbinom(nrow(d1), 1, plogis(1 + 0.5 * (d1$A == "a2") - 0.2 * (d1$B == "b2") + u1[as.integer(factor(d1$s))]))
write_data(d1, "balanced_2x2.csv")

d2 <- make_trials(102, 20, list(A = c("a1", "a2"), B = c("b1", "b2")), 10, items = 12)
set.seed(202)
d2 <- d2[runif(nrow(d2)) > 0.2, ]             # unbalanced: 20% of trials never recorded
d2$time[sample(nrow(d2), 25)] <- NA           # missing trials: recorded without a time
write_data(d2, "unbalanced_items.csv")

d3 <- make_trials(103, 16, list(A = c("a1", "a2", "a3")), 6, effects = list(A = c(0, 0.2, 0.5)))
d3$y <- round(100 * d3$time, 3)               # an untransformed measure in other units
write_data(d3, "one_factor_3.csv")

d4 <- make_trials(104, 12, list(A = c("a1", "a2"), B = c("b1", "b2", "b3"), C = c("c1", "c2")), 4)
write_data(d4, "three_factor.csv")

d5 <- make_trials(105, 18, list(A = c("a1", "a2", "a3")), 5,
                  between = list(name = "G", levels = c("g1", "g2"), sizes = c(7, 11), effect = c(0, 0.25)))
write_data(d5, "between_unequal.csv")

d6 <- make_trials(106, 15, list(A = c("a1", "a2")), 6, sd_s = 0, sd_slope = 0, items = 1)
ls6 <- log(d6$time)                            # no subject variance at all: each subject's mean residual
d6$time <- round(exp(ls6 - ave(ls6, d6$s) + mean(ls6) + 0.3 * (d6$A == "a2")), 6)   # removed (singular fit)
write_data(d6, "singular.csv")

d7 <- make_trials(107, 15, list(A = c("a1", "a2")), 6, sd_s = 0.08, sd_slope = 0, sd_e = 1)
write_data(d7, "near_zero.csv")

d8 <- d1[, names(d1) != "correct"]
d8$time <- fmt17(1e6 + d1$time)               # large offset: 1e6 added to every time
write_data(d8, "offset_1e6.csv")

make_binary <- function(seed, p_a1, p_a2, ns = 20, trials = 12, sd = 0.5) {
  set.seed(seed)
  d <- expand.grid(trial = seq_len(trials), A = c("a1", "a2"), s = sprintf("s%02d", seq_len(ns)),
                   stringsAsFactors = FALSE)[, c("s", "A", "trial")]
  u <- rnorm(ns, 0, sd)
  d$y <- rbinom(nrow(d), 1, plogis(qlogis(ifelse(d$A == "a1", p_a1, p_a2)) + u[as.integer(factor(d$s))]))
  d
}
write_data(make_binary(401, 0.02, 0.05), "binary_rare.csv")          # about 3% ones
write_data(make_binary(402, 0.97, 0.995), "binary_near_perfect.csv") # about 99% ones
sep <- make_binary(403, 0.7, 0.999)
sep$y[sep$A == "a2"] <- 1                                             # every a2 trial correct: separation
write_data(sep, "binary_separated.csv")

# ---- fitting and recording --------------------------------------------------
cases <- list()

quiet_fit <- function(expr) {
  msgs <- character(); warns <- character()
  m <- withCallingHandlers(expr,
    message = function(c) { msgs <<- c(msgs, trimws(conditionMessage(c))); invokeRestart("muffleMessage") },
    warning = function(w) { warns <<- c(warns, conditionMessage(w)); invokeRestart("muffleWarning") })
  list(m = m, messages = msgs, warnings = warns)
}

prepare <- function(file, factors, groups, re_columns = FALSE) {
  d <- read.csv(file)
  for (v in factors) d[[v]] <- factor(d[[v]], levels = sort(unique(as.character(d[[v]]))))
  for (v in groups) d[[v]] <- factor(d[[v]])
  if (re_columns) {
    X <- model.matrix(as.formula(paste("~", paste(factors, collapse = "*"))), d)
    for (cn in colnames(X)[-1]) d[[paste0("re_", gsub("[^A-Za-z0-9]", "_", cn))]] <- X[, cn]
  }
  d
}

emm_record <- function(m, spec) {
  e <- emmeans(m, as.formula(paste("~", paste(spec, collapse = "*"))), lmer.df = "satterthwaite",
               lmerTest.limit = Inf)
  s <- as.data.frame(summary(e))
  p <- as.data.frame(summary(pairs(e, adjust = "holm"), infer = c(FALSE, TRUE)))
  pu <- as.data.frame(confint(pairs(e, adjust = "none")))
  list(factors = spec, emmean = s$emmean, se = s$SE, df = s$df, lower = s$lower.CL, upper = s$upper.CL,
       contrast = as.character(p$contrast), c_estimate = p$estimate, c_se = p$SE, c_df = p$df,
       c_t = p$t.ratio, c_p_holm = p$p.value, c_lower = pu$lower.CL, c_upper = pu$upper.CL)
}

record_lmm <- function(name, file, dv, subject, within, between = character(), item = "", random = "intercepts",
                       transform = "none", reml = TRUE, formula, re_columns = FALSE, emm = list(),
                       kr = FALSE, note = "", lrt = FALSE, steps = NULL) {
  factors <- c(within, between)
  groups <- c(subject, if (nchar(item)) item)
  d <- prepare(file, factors, groups, re_columns)
  call <- sprintf("lmerTest::lmer(%s, data = d, REML = %s)", formula, reml)
  f <- quiet_fit(lmer(as.formula(formula), data = d, REML = reml))
  m <- f$m
  cs <- coef(summary(m))
  a <- anova(m)
  vc <- as.data.frame(VarCorr(m))
  rec <- list(name = name, data = file, note = note,
    options = list(dv = dv, subject = subject, within = within, between = between, item = item,
                   random = random, transform = transform, reml = reml, family = "gaussian"),
    r_call = paste0("options(contrasts = c(\"contr.sum\", \"contr.poly\")); d <- read.csv(\"", file,
                    "\") with factor levels sorted; m <- ", call, "; summary(m); anova(m); VarCorr(m); ",
                    "emmeans(m, ~ F, lmer.df = \"satterthwaite\", lmerTest.limit = Inf); pairs(., adjust = \"holm\")"),
    formula = formula,
    theta = unname(getME(m, "theta")),
    criterion = if (reml) REMLcrit(m) else deviance(m),
    loglik = as.numeric(logLik(m)), aic = AIC(m), bic = BIC(m), sigma = sigma(m),
    singular = isSingular(m), messages = f$messages, warnings = f$warnings,
    coef_names = rownames(cs), estimate = unname(cs[, "Estimate"]), se = unname(cs[, "Std. Error"]),
    df = unname(cs[, "df"]), t = unname(cs[, "t value"]), p = unname(cs[, "Pr(>|t|)"]),
    anova_terms = rownames(a), F = a[["F value"]], num_df = a$NumDF, den_df = a$DenDF, anova_p = a[["Pr(>F)"]],
    sum_sq = a[["Sum Sq"]],
    vc_group = vc$grp, vc_var1 = ifelse(is.na(vc$var1), "", vc$var1), vc_var2 = ifelse(is.na(vc$var2), "", vc$var2),
    vc_vcov = vc$vcov, vc_sdcor = vc$sdcor,
    emmeans = lapply(emm, function(spec) emm_record(m, spec)))
  if (kr) {
    ak <- anova(m, ddf = "Kenward-Roger")
    ck <- coef(summary(m, ddf = "Kenward-Roger"))
    rec$kr <- list(r_call = sprintf("anova(m, ddf = \"Kenward-Roger\"); coef(summary(m, ddf = \"Kenward-Roger\"))"),
                   F = ak[["F value"]], num_df = ak$NumDF, den_df = ak$DenDF, p = ak[["Pr(>F)"]],
                   se = unname(ck[, "Std. Error"]), df = unname(ck[, "df"]), coef_p = unname(ck[, "Pr(>|t|)"]))
  }
  if (lrt) {
    a_lrt <- afex::mixed(as.formula(formula), data = d, method = "LRT", progress = FALSE)$anova_table
    rec$lrt <- list(r_call = sprintf("afex::mixed(%s, data = d, method = \"LRT\")", formula),
                    terms = rownames(a_lrt), chisq = a_lrt$Chisq, df = a_lrt[["Chi Df"]], p = a_lrt[["Pr(>Chisq)"]])
  }
  if (!is.null(steps)) rec$steps <- steps
  cat("\n=====", name, "\n", call, "\n")
  print(summary(m)); print(a)
  cases[[length(cases) + 1]] <<- rec
}

record_lmm("balanced_intercepts", "balanced_2x2.csv", "time", "s", c("A", "B"), transform = "log",
           formula = "log(time) ~ A * B + (1 | s)", emm = list("A", "B", c("A", "B")), kr = TRUE, lrt = TRUE)
record_lmm("balanced_slopes", "balanced_2x2.csv", "time", "s", c("A", "B"), random = "slopes", transform = "log",
           formula = "log(time) ~ A * B + (1 + A + B | s)", emm = list("A", c("A", "B")),
           note = "path sensitive: 6 variance parameters; lme4's BOBYQA path moves with the last bit of the criterion")
record_lmm("balanced_ml", "balanced_2x2.csv", "time", "s", c("A", "B"), transform = "log", reml = FALSE,
           formula = "log(time) ~ A * B + (1 | s)", emm = list("A"))
record_lmm("unbalanced_items", "unbalanced_items.csv", "time", "s", c("A", "B"), item = "item",
           transform = "log", formula = "log(time) ~ A * B + (1 | s) + (1 | item)",
           emm = list("A", c("A", "B")), kr = TRUE)
record_lmm("one_factor_raw", "one_factor_3.csv", "y", "s", "A",
           formula = "y ~ A + (1 | s)", emm = list("A"), kr = TRUE)
record_lmm("one_factor_slopes", "one_factor_3.csv", "y", "s", "A", random = "slopes",
           formula = "y ~ A + (1 + A | s)", emm = list("A"),
           note = "path sensitive: 6 variance parameters, singular; lme4's BOBYQA path moves with the last bit of the criterion")
record_lmm("three_factor", "three_factor.csv", "time", "s", c("A", "B", "C"), transform = "log",
           formula = "log(time) ~ A * B * C + (1 | s)", emm = list("B", c("A", "C")), kr = TRUE)
record_lmm("between_unequal", "between_unequal.csv", "time", "s", "A", between = "G", transform = "log",
           formula = "log(time) ~ A * G + (1 | s)", emm = list("A", "G", c("A", "G")), kr = TRUE)
record_lmm("singular", "singular.csv", "time", "s", "A", transform = "log",
           formula = "log(time) ~ A + (1 | s)", emm = list("A"))
record_lmm("near_zero", "near_zero.csv", "time", "s", "A", transform = "log",
           formula = "log(time) ~ A + (1 | s)", emm = list("A"))
record_lmm("offset_1e6", "offset_1e6.csv", "time", "s", c("A", "B"),
           formula = "time ~ A * B + (1 | s)", emm = list("A"))

# ---- binomial GLMMs ----------------------------------------------------------
# lme4's defaults stop PIRLS at a relative change of 1e-7 (noise of ~1e-5 in the
# criterion) and Nelder-Mead at FtolAbs = 1e-5, so its estimates sit within
# ~1e-4 of the Laplace optimum. The reference is therefore the same model fitted
# to the optimum (control "tight"); glmer's default fit is recorded beside it.
tight <- glmerControl(tolPwrss = 1e-13, optimizer = "nloptwrap",
                      optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14, maxeval = 1e5))
tight_text <- paste0("glmerControl(tolPwrss = 1e-13, optimizer = \"nloptwrap\", optCtrl = list(xtol_abs = 1e-14, ",
                     "ftol_abs = 1e-15, xtol_rel = 1e-14, maxeval = 1e5))")

glmm_summary <- function(m, devfun) {
  par <- c(getME(m, "theta"), fixef(m))
  nt <- length(getME(m, "theta"))
  # SEs from numDeriv's Richardson Hessian of the Laplace criterion at the optimum:
  # free of the finite-difference noise of deriv12 (vcov.merMod's default)
  H <- numDeriv::hessian(devfun, par)
  V <- 2 * solve(H)[-seq_len(nt), -seq_len(nt), drop = FALSE]
  list(theta = unname(getME(m, "theta")), estimate = unname(fixef(m)), se = sqrt(diag(V)),
       se_lme4 = unname(sqrt(diag(as.matrix(vcov(m))))), loglik = as.numeric(logLik(m)), aic = AIC(m), bic = BIC(m))
}

record_glmm <- function(name, file, dv, subject, within, formula, emm = list(), lrt = TRUE) {
  d <- prepare(file, within, subject)
  f <- as.formula(formula)
  def <- quiet_fit(glmer(f, data = d, family = binomial))
  tf <- quiet_fit(glmer(f, data = d, family = binomial, control = tight))
  devfun <- glmer(f, data = d, family = binomial, control = tight, devFunOnly = TRUE)
  rec <- list(name = name, data = file, note = "",
    options = list(dv = dv, subject = subject, within = within, between = character(), item = "",
                   random = "intercepts", transform = "none", reml = FALSE, family = "binomial"),
    r_call = paste0("m <- lme4::glmer(", formula, ", data = d, family = binomial, control = ", tight_text,
                    "); SE from numDeriv::hessian of its devFunOnly at the optimum"),
    formula = formula, tight = glmm_summary(tf$m, devfun),
    default = c(list(r_call = paste0("lme4::glmer(", formula, ", data = d, family = binomial)")),
                glmm_summary(def$m, devfun)),
    coef_names = names(fixef(tf$m)),
    singular = isSingular(tf$m), messages = def$messages, warnings = def$warnings)
  if (lrt) {
    X <- model.matrix(tf$m)
    asg <- attr(X, "assign")
    labels <- attr(terms(tf$m), "term.labels")
    rec$lrt <- list(r_call = paste0("afex::mixed(", formula, ", data = d, family = binomial, method = \"LRT\", ",
                                    "control = ", tight_text, ")"),
                    terms = labels, chisq = numeric(), df = numeric(), p = numeric())
    a <- afex::mixed(f, data = d, family = binomial, method = "LRT", control = tight, progress = FALSE)$anova_table
    rec$lrt$chisq <- a$Chisq
    rec$lrt$df <- a[["Chi Df"]]
    rec$lrt$p <- a[["Pr(>Chisq)"]]
  }
  if (length(emm)) {
    rec$emmeans <- lapply(emm, function(spec) {
      e <- emmeans(tf$m, as.formula(paste("~", paste(spec, collapse = "*"))))
      s <- as.data.frame(summary(e))
      p <- as.data.frame(summary(pairs(e, adjust = "holm"), infer = c(FALSE, TRUE)))
      list(factors = spec, emmean = s$emmean, se = s$SE, contrast = as.character(p$contrast),
           c_estimate = p$estimate, c_se = p$SE, c_z = p$z.ratio, c_p_holm = p$p.value)
    })
  }
  cat("\n=====", name, "\n"); print(summary(tf$m))
  cases[[length(cases) + 1]] <<- rec
}

record_glmm("binomial_basic", "balanced_2x2.csv", "correct", "s", c("A", "B"),
            "correct ~ A * B + (1 | s)", emm = list("A", c("A", "B")))
record_glmm("binomial_rare", "binary_rare.csv", "y", "s", "A", "y ~ A + (1 | s)", emm = list("A"))
record_glmm("binomial_near_perfect", "binary_near_perfect.csv", "y", "s", "A", "y ~ A + (1 | s)", emm = list("A"))

# Complete separation (every a2 trial correct): glmer's default fit warns and
# returns arbitrary large estimates; fitted to the optimum it stops with
# "Downdated VtV is not positive definite". Recorded: the default fit.
d <- prepare("binary_separated.csv", "A", "s")
sep_default <- quiet_fit(glmer(y ~ A + (1 | s), data = d, family = binomial))
sep_tight <- tryCatch(glmer(y ~ A + (1 | s), data = d, family = binomial, control = tight),
                      error = function(e) conditionMessage(e))
cases[[length(cases) + 1]] <- list(name = "binomial_separated", data = "binary_separated.csv",
  options = list(dv = "y", subject = "s", within = "A", between = character(), item = "", random = "intercepts",
                 transform = "none", reml = FALSE, family = "binomial"),
  r_call = "lme4::glmer(y ~ A + (1 | s), data = d, family = binomial)", formula = "y ~ A + (1 | s)",
  theta = unname(getME(sep_default$m, "theta")), loglik = as.numeric(logLik(sep_default$m)),
  estimate = unname(fixef(sep_default$m)), messages = sep_default$messages, warnings = sep_default$warnings,
  tight_error = if (is.character(sep_tight)) sep_tight else "")
cat("\n===== binomial_separated\n"); print(summary(sep_default$m)); print(sep_default$warnings); print(sep_tight)

# ---- --random max: the parsimonious fallback, decided by lme4's own verdicts ----
# The maximal model, then the || model with numeric contr.sum columns, then the
# slope with the smallest variance dropped, until lme4 neither calls the fit
# singular nor warns. Every step's formula and lme4's verdict is recorded.
fallback <- function(file, dvexpr, factors, subject, item) {
  d <- prepare(file, factors, c(subject, item), re_columns = TRUE)
  X <- model.matrix(as.formula(paste("~", paste(factors, collapse = "*"))), d)
  cols <- colnames(X)[-1]
  recols <- paste0("re_", gsub("[^A-Za-z0-9]", "_", cols))
  fixed <- paste(dvexpr, "~", paste(factors, collapse = " * "))
  labels <- attr(terms(as.formula(fixed)), "term.labels")
  max_re <- paste(c("1", labels), collapse = " + ")
  formula <- paste0(fixed, " + (", max_re, " | ", subject, ") + (", max_re, " | ", item, ")")
  steps <- list()
  verdict <- function(f) {
    r <- quiet_fit(lmer(as.formula(f), data = d, REML = TRUE))
    list(fit = r, regular = !isSingular(r$m) && length(r$warnings) == 0)
  }
  v <- verdict(formula)
  steps[[1]] <- list(formula = formula, singular = isSingular(v$fit$m), warnings = v$fit$warnings)
  if (v$regular) return(list(formula = formula, steps = steps))
  keep <- list(s = recols, i = recols)
  zcp <- function() paste0(fixed, " + (", paste(c("1", keep$s), collapse = " + "), if (length(keep$s)) " || " else " | ",
                           subject, ") + (", paste(c("1", keep$i), collapse = " + "), if (length(keep$i)) " || " else " | ",
                           item, ")")
  repeat {
    formula <- zcp()
    v <- verdict(formula)
    steps[[length(steps) + 1]] <- list(formula = formula, singular = isSingular(v$fit$m), warnings = v$fit$warnings)
    if (v$regular || (length(keep$s) + length(keep$i)) == 0) break
    vc <- as.data.frame(VarCorr(v$fit$m))
    vc <- vc[vc$var1 %in% recols & is.na(vc$var2), ]
    k <- which.min(vc$vcov)
    g <- if (startsWith(vc$grp[k], subject)) "s" else "i"
    keep[[g]] <- setdiff(keep[[g]], vc$var1[k])
  }
  list(formula = formula, steps = steps)
}
fb <- fallback("unbalanced_items.csv", "log(time)", c("A", "B"), "s", "item")
record_lmm("max_fallback", "unbalanced_items.csv", "time", "s", c("A", "B"), item = "item", random = "max",
           transform = "log", formula = fb$formula, re_columns = TRUE, emm = list("A"), steps = fb$steps,
           note = "path sensitive: the || model's several variance parameters")

writeLines(toJSON(list(generated_by = "make_lmm_reference.R", r = R.version.string,
                       packages = sapply(c("lme4", "lmerTest", "pbkrtest", "emmeans", "afex", "nloptr"),
                                         function(p) as.character(packageVersion(p))),
                       cases = cases), digits = NA, auto_unbox = TRUE, pretty = TRUE), "lmm_reference.json")
