# Reference values for test_report_published.cpp (ReportPublished.OneFactorThreeLevelsMatchesPingouinAndFriedmanMatchesR):
# the Iman-Davenport F test of report.json's Friedman entry, whose fields are those of `dtlab stats friedman --json`
# (analysis/stats/json.h). Data: R's friedman.test example RoundingTimes (Hollander & Wolfe 1973), 22 blocks x 3.
# Run: Rscript friedman_iman_davenport.R > friedman_iman_davenport.Rout (R only; the test never needs R).
RoundingTimes <- matrix(c(5.40, 5.50, 5.55, 5.85, 5.70, 5.75, 5.20, 5.60, 5.50, 5.55, 5.50, 5.40, 5.90, 5.85, 5.70,
                          5.45, 5.55, 5.60, 5.40, 5.40, 5.35, 5.45, 5.50, 5.35, 5.25, 5.15, 5.00, 5.85, 5.80, 5.70,
                          5.25, 5.20, 5.10, 5.65, 5.55, 5.45, 5.60, 5.35, 5.45, 5.05, 5.00, 4.95, 5.50, 5.50, 5.40,
                          5.45, 5.55, 5.50, 5.55, 5.55, 5.35, 5.45, 5.50, 5.55, 5.50, 5.45, 5.25, 5.65, 5.60, 5.40,
                          5.70, 5.65, 5.55, 6.30, 6.30, 6.25),
                        nrow = 22, byrow = TRUE)
n <- nrow(RoundingTimes); k <- ncol(RoundingTimes)
Q <- unname(friedman.test(RoundingTimes)$statistic)
F <- (n - 1) * Q / (n * (k - 1) - Q)          # Iman & Davenport (1980)
df1 <- k - 1; df2 <- (k - 1) * (n - 1)
p <- pf(F, df1, df2, lower.tail = FALSE)
ties <- any(apply(RoundingTimes, 1, function(r) any(duplicated(r))))
print(c(Q = Q, F = F, df1 = df1, df2 = df2, p = p), digits = 12)
print(ties)
