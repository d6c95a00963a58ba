# Reference values for tests/analysis/report/test_report_instruments.cpp:
# the data of a pilot-design study with NASA-TLX after every block and a
# 7-point Likert item after each transparency level (drawn once here with a
# fixed seed and written to instruments_tlx.csv and instruments_ease.csv,
# which the test's fixture stores answer by answer), then the raw TLX per
# condition and the tests the report must reproduce.
# Run: Rscript tests/analysis/data/instruments_r_references.R
#      > tests/analysis/data/instruments_r_references.Rout
suppressMessages(library(afex))
set.seed(20240624)
dir <- if (file.exists("tests/analysis/data")) "tests/analysis/data" else "."
grid <- expand.grid(scenario = c("abstract", "walkthrough"), transparency = c("off", "on"),
                    participant = sprintf("P%d", 1:8), stringsAsFactors = FALSE)[, 3:1]
# TLX ratings: 0..100 in steps of 5; "off" and "walkthrough" a little more demanding.
lift <- 15 * (grid$transparency == "off") + 5 * (grid$scenario == "walkthrough")
dims <- c("mental", "physical", "temporal", "performance", "effort", "frustration")
for (d in dims) grid[[d]] <- pmin(100, pmax(0, 5 * round((35 + lift + rnorm(nrow(grid), 0, 15)) / 5)))
grid$physical <- pmin(grid$physical, 40)
write.csv(grid, file.path(dir, "instruments_tlx.csv"), row.names = FALSE)
ease <- expand.grid(transparency = c("off", "on"), participant = sprintf("P%d", 1:8), stringsAsFactors = FALSE)[, 2:1]
ease$ease <- pmin(7, pmax(1, round(4 + 1.2 * (ease$transparency == "on") + rnorm(nrow(ease), 0, 1.2))))
write.csv(ease, file.path(dir, "instruments_ease.csv"), row.names = FALSE)

tlx <- read.csv(file.path(dir, "instruments_tlx.csv"))
tlx$raw <- rowMeans(tlx[, dims])
cat("raw TLX per cell (mean, sd):\n")
print(aggregate(raw ~ transparency + scenario, tlx, function(x) c(mean = mean(x), sd = sd(x))), digits = 15)
a <- aov_ez(id = "participant", dv = "raw", data = tlx, within = c("transparency", "scenario"),
            anova_table = list(correction = "none", es = "pes"))
cat("\naov_ez(id = \"participant\", dv = \"raw\", within = c(\"transparency\", \"scenario\"))\n")
print(format(as.data.frame(a$anova_table), digits = 15))
e <- read.csv(file.path(dir, "instruments_ease.csv"))
cat("\nfriedman.test(ease ~ transparency | participant)\n")
f <- friedman.test(ease ~ transparency | participant, data = e)
print(c(statistic = unname(f$statistic), df = unname(f$parameter), p = f$p.value), digits = 15)
cat("\nease per level (mean, sd):\n")
print(aggregate(ease ~ transparency, e, function(x) c(mean = mean(x), sd = sd(x))), digits = 15)
