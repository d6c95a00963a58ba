# R 4.2.2 (Debian r-base-core 4.2.2.20221110-2) with afex 1.2.1, emmeans 1.8.4.1,
# car 3.1-1 and effectsize 0.8.3 (Debian r-cran-effectsize): the calls behind the
# values quoted in tests/analysis/stats/test_mixed_followups.cpp, test_ties_and_scale.cpp (aggregated ties,
# mixed-design post-hoc tests and simple effects as emmeans gives them on the
# afex fit, afex's MSE beside corrected df, effectsize's eta_p2 interval,
# values near the smallest double, many within levels) and
# tests/analysis/report/test_report_planning.cpp (the df of a GG-corrected p).
# Run from the repository root:
#   Rscript tests/analysis/data/stats_r_followups.R > tests/analysis/data/stats_r_followups.Rout 2>&1
# The tests never need R: each value is written above its assertion.
suppressMessages({library(afex); library(emmeans); library(effectsize)})
options(digits = 15, width = 160)
data_dir <- "tests/analysis/data"
cat("R", R.version$major, R.version$minor, "afex", format(packageVersion("afex")), "emmeans",
    format(packageVersion("emmeans")), "effectsize", format(packageVersion("effectsize")), "\n")

cat("\n== 1. --aggregate mean keeps ties: aggregate_ties.csv\n")
d <- read.csv(file.path(data_dir, "aggregate_ties.csv"))
a <- aggregate(time ~ participant + condition, d, mean)
print(xtabs(time ~ participant + condition, a))
print(friedman.test(time ~ condition | participant, a))
w <- reshape(a, idvar = "participant", timevar = "condition", direction = "wide")
print(w$time.A - w$time.B)  # four differences are exactly 0
print(wilcox.test(w$time.A, w$time.B, paired = TRUE))

cat("\n== 2. A factor's marginal means tie (wilcoxon --factor): 2 x 2 within, B averaged\n")
m <- data.frame(id = rep(paste0("s", 1:5), each = 4), A = rep(c("a1", "a1", "a2", "a2"), 5),
                B = rep(c("b1", "b2"), 10),
                y = c(0.1, 0.3, 0.2, 0.2,   0.7, 0.1, 0.4, 0.4,   1.5, 0.9, 0.6, 0.8,
                      0.3, 0.6, 0.9, 0.1,   2.2, 2.4, 2.3, 2.3))
am <- aggregate(y ~ id + A, m, mean)
wa <- reshape(am, idvar = "id", timevar = "A", direction = "wide")
print(wa$y.a1 - wa$y.a2)  # s2: R's mean(c(0.7, 0.1)) is 0.39999999999999997, one ulp below mean(c(0.4, 0.4))
print(wilcox.test(wa$y.a1, wa$y.a2, paired = TRUE))
cat("the decimal means (what dtlab computes exactly: here round(, 12) gives them)\n")
am$y <- round(am$y, 12)
wa <- reshape(am, idvar = "id", timevar = "A", direction = "wide")
print(wa$y.a1 - wa$y.a2)
print(wilcox.test(wa$y.a1, wa$y.a2, paired = TRUE))

cat("\n== 3. Mixed design post-hoc: mixed_posthoc.csv, group (between) x task (within)\n")
d <- read.csv(file.path(data_dir, "mixed_posthoc.csv"))
fit <- aov_car(time ~ group + Error(id/task), d)
print(as.data.frame(pairs(emmeans(fit, ~ task), adjust = "none")))
print(as.data.frame(pairs(emmeans(fit, ~ task), adjust = "holm")))
print(as.data.frame(confint(pairs(emmeans(fit, ~ task), adjust = "none"))))
cat("what --posthoc gave before: paired t over all 12 subjects, ignoring the groups\n")
w <- reshape(d, idvar = c("id", "group"), timevar = "task", direction = "wide")
print(t.test(w$time.search, w$time.locate, paired = TRUE)$p.value)
cat("simple effects (emmeans levels are alphabetical: expert before novice)\n")
print(as.data.frame(joint_tests(fit, by = "group")))
print(as.data.frame(joint_tests(fit, by = "task")))
print(as.data.frame(pairs(emmeans(fit, ~ group | task))))
cat("Cohen's d of novice - expert at task = count: the estimate over the SD pooled over the groups\n")
x <- d[d$task == "count", ]
pooled <- sqrt(sum(tapply(x$time, x$group, function(v) sum((v - mean(v))^2))) / (nrow(x) - 2))
print(unname(diff(tapply(x$time, x$group, mean)) / pooled))

cat("\n== 4. obk_long.csv: treatment x gender (between) x phase x hour (within)\n")
o <- read.csv(file.path(data_dir, "obk_long.csv"))
o$id <- factor(o$id); o$hour <- factor(o$hour)
fo <- aov_car(value ~ treatment * gender + Error(id/(phase * hour)), o)
print(as.data.frame(pairs(emmeans(fo, ~ phase), adjust = "holm")))
jt <- as.data.frame(joint_tests(fo, by = "treatment"))
print(jt[jt$`model term` %in% c("phase", "hour", "gender"), ])
print(as.data.frame(pairs(emmeans(fo, ~ gender | treatment))))
print(as.data.frame(joint_tests(fo, by = "phase"))[1:6, ])

cat("\n== 5. md_12.1.csv: afex's MSE beside Greenhouse-Geisser df; effectsize's eta_p2 interval\n")
md <- read.csv(file.path(data_dir, "md_12.1.csv"))
md$id <- factor(md$id)
fm <- aov_car(rt ~ Error(id/(angle * noise)), md)
print(anova(fm))                       # correction = "GG" (afex's default): MSE = SS_error / den Df (GG)
print(anova(fm, correction = "HF"))
print(anova(fm, correction = "none"))
for (row in list(c(40.7191011235955, 2, 18), c(33.7659574468085, 1, 9), c(45.3103448275862, 2, 18)))
  print(as.data.frame(F_to_eta2(row[1], row[2], row[3], ci = 0.9, alternative = "two.sided")))

cat("\n== 6. Values near the smallest double: R gives NaN, the same data x 1e310 give F\n")
t <- read.csv(file.path(data_dir, "tiny_values.csv"))
t$id <- factor(t$id)
print(summary(aov(y ~ cond + Error(id/cond), t)))
t$y <- t$y * 1e155 * 1e155
print(summary(aov(y ~ cond + Error(id/cond), t)))
print(as.data.frame(anova(aov_car(y ~ Error(id/cond), t), correction = "GG")))
print(as.data.frame(anova(aov_car(y ~ Error(id/cond), t), correction = "none")))

cat("\n== 7. Many within levels: y = ((s 7919 + c 104729) mod 1000) / 10, 3 subjects x L levels\n")
mk <- function(L) {
  s <- rep(0:2, each = L); c <- rep(0:(L - 1), 3)
  data.frame(id = factor(paste0("s", s)), cond = factor(paste0("c", c), levels = paste0("c", 0:(L - 1))),
             y = ((s * 7919 + c * 104729) %% 1000) / 10)
}
print(summary(aov(y ~ cond + Error(id/cond), mk(300))))
# 3000 levels: aov() needs a 9000 x 3000 model matrix (minutes, gigabytes; aov_car's car::Anova fails on
# these data already at 300 levels: "invalid comparison with complex values"); the one-way within
# decomposition (Maxwell & Delaney ch. 11), which gives aov's F at 300 levels above:
one_way_within <- function(d) {
  L <- nlevels(d$cond); n <- nlevels(d$id); gm <- mean(d$y)
  cm <- tapply(d$y, d$cond, mean); sm <- tapply(d$y, d$id, mean)
  ss <- n * sum((cm - gm)^2); res <- d$y - sm[as.integer(d$id)] - cm[as.integer(d$cond)] + gm
  se <- sum(res^2); F <- (ss / (L - 1)) / (se / ((L - 1) * (n - 1)))
  c(SS = ss, SS_error = se, F = F, p = pf(F, L - 1, (L - 1) * (n - 1), lower.tail = FALSE),
    log10_p = pf(F, L - 1, (L - 1) * (n - 1), lower.tail = FALSE, log.p = TRUE) / log(10))
}
print(one_way_within(mk(300)))
print(one_way_within(mk(3000)))

cat("\n== 8. pingouin_rm_anova_wide.csv (complete subjects): the df of the GG-corrected p\n")
pw <- read.csv(file.path(data_dir, "pingouin_rm_anova_wide.csv"))
pw <- pw[complete.cases(pw), ]
pw$id <- factor(seq_len(nrow(pw)))
pl <- reshape(pw, direction = "long", varying = setdiff(names(pw), "id"), v.names = "score",
              timevar = "week", times = setdiff(names(pw), "id"), idvar = "id")
print(as.data.frame(anova(aov_car(score ~ Error(id/week), pl), correction = "GG")))
