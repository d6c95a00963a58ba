# R 4.2.2 (Debian r-base-core 4.2.2.20221110-2, car 3.1-1) calls that produced the reference values
# quoted in tests/analysis/stats/test_edge_cases.cpp, test_followup_power.cpp, test_assumptions_apa.cpp,
# test_posthoc_descriptives.cpp and test_anova_nist.cpp. Run from the repository root:
#   Rscript tests/analysis/data/stats_r_references.R > stats_r_references.Rout
# The tests never need R: each value is written above its assertion.
Y <- matrix(c(9999999, 20000001, 2, 20000001, 39999997, 4, 29999998, 60000001, 7, 50000002, 99999997, 3), 4, 3, byrow=TRUE)
fit <- lm(Y ~ 1)
print(mauchly.test(fit, X = ~1), digits=15)
library(car)
d <- data.frame(id=factor(rep(1:4,each=3)), cond=factor(rep(c("a","b","c"),4)), y=as.vector(t(Y)))
idata <- data.frame(cond=factor(c("a","b","c")))
a <- Anova(fit, idata=idata, idesign=~cond, type=3)
s <- summary(a, multivariate=FALSE)
print(s$sphericity.tests, digits=15)
print(s$pval.adjustments, digits=15)
print(s$univariate.tests, digits=15)
Y <- matrix(c(-2, 125000000000003, 250000000000003, 12, 125000000000008, 250000000000013, 17, 125000000000017, 250000000000020, 28, 125000000000032, 250000000000031),4,3,byrow=TRUE)
d <- data.frame(id=factor(rep(1:4,each=3)), cond=factor(rep(c("a","b","c"),4)), y=as.vector(t(Y)))
print(summary(aov(y ~ cond + Error(id/cond), d)), digits=15)
library(car)
fit <- lm(Y ~ 1); idata <- data.frame(cond=factor(c("a","b","c")))
s <- summary(Anova(fit, idata=idata, idesign=~cond, type=3), multivariate=FALSE)
print(s$univariate.tests, digits=15); print(s$sphericity.tests, digits=15); print(s$pval.adjustments, digits=15)
print(pf(2250000000000054000000000000327/163, 2, 6, lower.tail=FALSE), digits=15)
options(digits=15)
x <- sleep$extra[1:10]; y <- sleep$extra[11:20]
print(t.test(x, y, paired=TRUE, alternative="less")$conf.int)
print(t.test(x, y, paired=TRUE, alternative="greater")$conf.int)
print(t.test(x, y, paired=TRUE, alternative="less")$p.value)
print(t.test(x, y, paired=TRUE, alternative="greater")$p.value)
r <- try(t.test(c(5,6,7,8,9), c(4,5,6,7,8), paired=TRUE))
print(pairwise.t.test(PlantGrowth$weight, PlantGrowth$group, p.adjust.method="holm")$p.value)
print(pairwise.t.test(PlantGrowth$weight, PlantGrowth$group, p.adjust.method="none")$p.value)
print(p.adjust(c(0.01, 0.02, 0.03, 0.04, 0.05), "holm"))
print(p.adjust(c(0.04, 0.01, 0.03), "holm"))
print(p.adjust(c(0.5, 0.6), "holm"))
print(p.adjust(c(0.02, NA, 0.01), "holm"))
options(digits=15)
d <- data.frame(g = rep(c("a","b"), each = 3), y = c(1,2,3,4,6,8) * 1e-170)
print(summary(aov(y ~ g, d)))
d2 <- data.frame(g = rep(c("a","b"), each = 3), y = c(1,2,3,4,6,8))
print(summary(aov(y ~ g, d2))[[1]]$`F value`)
dd <- data.frame(id = factor(rep(c("a","b","c"), each = 2)), cond = factor(rep(c("x","y"), 3)), y = c(2, 5, 2, 6.5, 0, 3))
print(summary(aov(y ~ cond + Error(id/cond), dd)))
print(t.test(c(5,6.5,3), c(2,2,0), paired=TRUE))
options(digits=15)
p <- function(...) { r <- power.t.test(..., type="paired"); cat(r$n, r$delta, r$sd, r$power, "\n") }
p(n=20, delta=1, sd=2)
p(n=10, delta=0.5, sd=1)
p(n=10, delta=0.5, sd=1, alternative="one.sided")
p(n=10, delta=0.5, sd=1, strict=TRUE)
p(n=3, delta=0.1, sd=1, strict=TRUE)
p(n=200, delta=0.3, sd=1.5, sig.level=0.01)
p(delta=1, sd=1, power=0.9)
p(delta=0.5, sd=1, power=0.8)
p(delta=0.5, sd=1, power=0.8, tol=1e-12)
# G*Power-style RM within via pf with ncp
rm <- function(f, n, m, rho, eps=1, alpha=0.05) { df1 <- (m-1)*eps; df2 <- (n-1)*df1; l <- f^2*n*m*eps/(1-rho); pf(qf(1-alpha, df1, df2), df1, df2, ncp=l, lower.tail=FALSE) }
f <- sqrt(0.1/0.9)
cat("rm1", rm(f, 20, 3, 0.5), "\n")
cat("rm2", rm(sqrt(0.346/(1-0.346)), 9, 4, 0.5, 0.694), "\n")
cat("rm3", rm(sqrt(0.346/(1-0.346)), 9, 4, -0.1996, 0.694), "\n")
cat("rm4", rm(0.25, 28, 3, 0.5), "\n")
cat("rm5", rm(0.25, 12, 4, 0.3, 0.6), "\n")
# noncentral F CI reference: uniroot on pf(F, df1, df2, ncp)
ci <- function(F, df1, df2, level=0.9) {
  lo_t <- 1-(1-level)/2; hi_t <- (1-level)/2
  g <- function(t) { if (pf(F, df1, df2) <= t) return(0); uniroot(function(l) pf(F, df1, df2, ncp=l) - t, c(0, max(10, F*df1*10)), tol=1e-13)$root }
  l1 <- g(lo_t); l2 <- g(hi_t)
  c(l1, l2, l1/(l1+df1+df2+1), l2/(l2+df1+df2+1))
}
cat("ci1", ci(20.09, 1, 15), "\n")
cat("ci2", ci(40.72, 2, 18), "\n")
cat("ci3", ci(1.2, 2, 30), "\n")
cat("ci4", ci(0.3, 3, 40), "\n")
cat("ci5", ci(5.72, 2, 114), "\n")
options(digits=15)
d <- read.csv("tests/analysis/data/md_12.1.csv")
d$id <- factor(d$id); d$angle <- factor(d$angle); d$noise <- factor(d$noise, levels=c("absent","present"))
# angle at each noise level
ps <- c()
for (nz in c("absent","present")) {
  s <- subset(d, noise == nz)
  a <- summary(aov(rt ~ angle + Error(id/angle), s))
  tab <- a[["Error: id:angle"]][[1]]
  cat("angle at", nz, "F", tab$`F value`[1], "df", tab$Df, "p", tab$`Pr(>F)`[1], "\n")
  ps <- c(ps, tab$`Pr(>F)`[1])
}
cat("holm angle family", p.adjust(ps, "holm"), "\n")
ps <- c()
for (an in c("0","4","8")) {
  s <- subset(d, angle == an)
  x <- s$rt[s$noise=="absent"][order(s$id[s$noise=="absent"])]; y <- s$rt[s$noise=="present"][order(s$id[s$noise=="present"])]
  t <- t.test(x, y, paired=TRUE)
  dd <- x - y
  cat("noise at", an, "est", t$estimate, "se", t$stderr, "ci", t$conf.int, "t", t$statistic, "df", t$parameter, "p", t$p.value, "dz", mean(dd)/sd(dd), "\n")
  ps <- c(ps, t$p.value)
}
cat("holm noise family", p.adjust(ps, "holm"), "\n")
# Cousineau-Morey
options(digits=15)
d <- read.csv("tests/analysis/data/md_12.1.csv")
d$cell <- paste(d$noise, d$angle, sep=":")
Y <- tapply(d$rt, list(d$id, d$cell), mean)
Y <- Y[, c("absent:0","absent:4","absent:8","present:0","present:4","present:8")]
N <- nrow(Y); C <- ncol(Y)
Z <- Y - rowMeans(Y) + mean(Y)
se <- apply(Z, 2, sd) / sqrt(N) * sqrt(C / (C - 1))
q <- qt(0.975, N - 1)
print(rbind(mean=colMeans(Y), se=se, lo=colMeans(Y) - q*se, hi=colMeans(Y) + q*se))
options(digits=15)
a <- c(0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0)
b <- c(1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4)
c <- c(1.0, 0.5, 0.2, 0.3, 0.9, 3.0, 4.1, 1.2, 2.2, 2.5)
y <- c(a, b, c); g <- factor(rep(c("a","b","c"), each=10))
print(pairwise.t.test(y, g, paired=TRUE, p.adjust.method="holm")$p.value)
for (pr in list(c("a","b"),c("a","c"),c("b","c"))) { x <- get(pr[1]); z <- get(pr[2]); t <- t.test(x, z, paired=TRUE); cat(pr, t$estimate, t$stderr, t$conf.int, t$statistic, t$p.value, mean(x-z)/sd(x-z), "\n") }
# pooled (PlantGrowth) CIs
m <- tapply(PlantGrowth$weight, PlantGrowth$group, mean); s <- sqrt(sum(tapply(PlantGrowth$weight, PlantGrowth$group, function(v) sum((v-mean(v))^2)))/27)
se <- s*sqrt(2/10); cat("pooled se", se, "trt1-ctrl", m[2]-m[1], (m[2]-m[1]) + c(-1,1)*qt(.975,27)*se, "\n")
options(digits=15)
a <- c(0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0)
b <- c(1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4)
c <- c(1.0, 0.5, 0.2, 0.3, 0.9, 3.0, 4.1, 1.2, 2.2, 2.5)
y <- c(a, b, c); g <- factor(rep(c("a","b","c"), each=10))
print(suppressWarnings(pairwise.wilcox.test(y, g, paired=TRUE, p.adjust.method="none")$p.value))
options(digits=15)
d <- read.csv("tests/analysis/data/md_12.1.csv")
d$cell <- paste(d$noise, d$angle, sep=":")
Y <- tapply(d$rt, list(d$id, d$cell), mean)
Y <- Y[, c("absent:0","absent:4","absent:8","present:0","present:4","present:8")]
E <- Y - outer(rowMeans(Y), rep(1, 6)) - outer(rep(1, 10), colMeans(Y)) + mean(Y)
print(E[1,]); r <- shapiro.test(as.vector(t(E))); cat(r$statistic, r$p.value, "\n")
# same residuals from aov: the id:cell stratum residuals
fit <- aov(rt ~ cell + Error(factor(id)), d)
options(digits=15)
men <- c(148, 154, 158, 160, 161, 162, 166, 170, 182, 195, 236)
r <- shapiro.test(men); cat("men", r$statistic, r$p.value, "\n")
r <- shapiro.test(sleep$extra); cat("sleep", r$statistic, r$p.value, "\n")
r <- shapiro.test(PlantGrowth$weight); cat("plant", r$statistic, r$p.value, "\n")
r <- shapiro.test(c(1, 2, 4)); cat("n3", r$statistic, r$p.value, "\n")
r <- shapiro.test(c(1, 2, 4, 9)); cat("n4", r$statistic, r$p.value, "\n")
r <- shapiro.test(c(2.1, 3.5, 1.0, 7.7, 4.4)); cat("n5", r$statistic, r$p.value, "\n")
g <- function(n) ((1:n * 37) %% 101)^2 / 7
for (n in c(6, 11, 12, 50, 200, 5000)) { r <- shapiro.test(g(n)); cat("gen", n, r$statistic, r$p.value, "\n") }
h <- function(n) ((1:n * 7919) %% 1009) - 504
for (n in c(20, 1000)) { r <- shapiro.test(h(n)); cat("unif", n, r$statistic, r$p.value, "\n") }
r <- shapiro.test(c(1,1,1,1,1,1,1,1,1,100)); cat("outlier", r$statistic, r$p.value, "\n")
