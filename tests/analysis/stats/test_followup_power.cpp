// Follow-ups of an ANOVA (simple effects, within-subject CIs), power, and the
// post-hoc table's columns, against R 4.2.2 (the call above each value).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/stats/followup.h"
#include "analysis/stats/power.h"
#include "analysis/stats/rm_anova.h"
#include "study/common/random.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;

LongData md() { return test::load_long("md_12.1.csv", {"rt", "id", {"noise", "angle"}, {}}); }

// d <- read.csv("md_12.1.csv"), factors as in the file (noise: absent, present; angle 0, 4, 8).
// Angle at each noise level:  summary(aov(rt ~ angle + Error(id/angle), subset(d, noise == nz)))
// Noise at each angle:        t.test(x, y, paired = TRUE) with x = absent, y = present (ordered by id)
// Holm within each family:    p.adjust(ps, "holm")
TEST(SimpleEffects, MaxwellDelaneyAgainstRSubsets) {
  auto r = simple_effects(md(), "angle", "noise");
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->rows.size(), 5u);
  const SimpleEffect& absent = r->rows[0];
  EXPECT_EQ(absent.factor, "angle");
  EXPECT_EQ(absent.at_level, "absent");
  EXPECT_EQ(absent.test, "rm-anova");
  // R: F 5.04624277456648 df 2 18 p 0.0182029195941228; present: F 77.0220994475139 p 1.50207717109326e-09
  EXPECT_TRUE(near_rel(absent.anova.F, 5.04624277456648, 1e-12));
  EXPECT_EQ(absent.anova.df2, 18);
  EXPECT_TRUE(near_rel(absent.p, 0.0182029195941228, 1e-10));
  EXPECT_TRUE(near_rel(r->rows[1].anova.F, 77.0220994475139, 1e-12));
  // R: p.adjust(c(0.0182029195941228, 1.50207717109326e-09), "holm") -> 0.0182029195941228 3.00415434218652e-09
  EXPECT_TRUE(near_rel(absent.p_holm, 0.0182029195941228, 1e-10));
  EXPECT_TRUE(near_rel(r->rows[1].p_holm, 3.00415434218652e-09, 1e-9));
  // Noise at angle 4: est -150 se 33.7638860322683 ci -226.379216631798 -73.6207833682021
  //   t -4.44261658319319 df 9 p 0.00161736377660557 dz -1.40487871737254
  const SimpleEffect& at4 = r->rows[3];
  EXPECT_EQ(at4.factor, "noise");
  EXPECT_EQ(at4.at_level, "4");
  EXPECT_EQ(at4.test, "paired t");
  EXPECT_TRUE(near_rel(at4.contrast.estimate, -150, 1e-13));
  EXPECT_TRUE(near_rel(at4.contrast.se, 33.7638860322683, 1e-12));
  EXPECT_TRUE(near_rel(at4.contrast.ci_low, -226.379216631798, 1e-12));
  EXPECT_TRUE(near_rel(at4.contrast.ci_high, -73.6207833682021, 1e-12));
  EXPECT_TRUE(near_rel(at4.contrast.statistic, -4.44261658319319, 1e-12));
  EXPECT_EQ(at4.contrast.df, 9);
  EXPECT_TRUE(near_rel(at4.p, 0.00161736377660557, 1e-10));
  EXPECT_TRUE(near_rel(at4.contrast.dz, -1.40487871737254, 1e-12));
  // R: p.adjust(c(0.244333143867479, 0.00161736377660557, 1.37591351423015e-06), "holm")
  //   -> 0.244333143867479 0.00323472755321114 4.12774054269044e-06
  EXPECT_TRUE(near_rel(r->rows[2].p_holm, 0.244333143867479, 1e-10));
  EXPECT_TRUE(near_rel(at4.p_holm, 0.00323472755321114, 1e-10));
  EXPECT_TRUE(near_rel(r->rows[4].p_holm, 4.12774054269044e-06, 1e-9));
  EXPECT_FALSE(simple_effects(md(), "angle", "angle").ok());
  EXPECT_FALSE(simple_effects(md(), "angle", "colour").ok());
}

// Cousineau-Morey, evaluated in R on the same data:
//   Y <- subject x cell matrix (cells absent:0, absent:4, absent:8, present:0, present:4, present:8)
//   Z <- Y - rowMeans(Y) + mean(Y); se <- apply(Z, 2, sd) / sqrt(N) * sqrt(C / (C - 1)); q <- qt(0.975, N - 1)
//   se: 17.0528589978338 25.1634655800826 11.7132403714771 18.8361354847538 16.7690190530037 21.2320512433443
//   lo (absent:0) 423.4237528718625, hi (present:8) 810.0302368010299
TEST(WithinSubjectIntervals, CousineauMoreyAsTheFormulaInR) {
  auto r = within_subject_intervals(md());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->size(), 6u);
  const double se[] = {17.0528589978338, 25.1634655800826, 11.7132403714771,
                       18.8361354847538, 16.7690190530037, 21.2320512433443};
  const double mean[] = {462, 510, 528, 492, 660, 762};
  for (size_t c = 0; c < 6; ++c) {
    EXPECT_TRUE(near_rel((*r)[c].se, se[c], 1e-12)) << c;
    EXPECT_TRUE(near_rel((*r)[c].mean, mean[c], 1e-14)) << c;
  }
  EXPECT_EQ((*r)[0].levels[0].second, "absent");
  EXPECT_EQ((*r)[0].levels[1].second, "0");
  EXPECT_TRUE(near_rel((*r)[0].ci_low, 423.4237528718625, 1e-13));
  EXPECT_TRUE(near_rel((*r)[5].ci_high, 810.0302368010299, 1e-13));
}

// R 4.2.2: power.t.test(n, delta, sd, sig.level, type = "paired", ...)$power
struct PairedPowerCase {
  double n, delta, sd, alpha;
  Alternative alt;
  bool strict;
  double power;
};

TEST(Power, PairedTEqualsPowerTTest) {
  const std::vector<PairedPowerCase> cases{
      {20, 1, 2, 0.05, Alternative::two_sided, false, 0.564482896678662},   // power.t.test(n=20, delta=1, sd=2, type="paired")
      {10, 0.5, 1, 0.05, Alternative::two_sided, false, 0.292828567266819}, // n=10, delta=0.5
      {10, 0.5, 1, 0.05, Alternative::greater, false, 0.427289826771351},   // alternative="one.sided"
      {10, 0.5, 1, 0.05, Alternative::two_sided, true, 0.293175606514385},  // strict=TRUE
      {3, 0.1, 1, 0.05, Alternative::two_sided, true, 0.0513883595146488},  // n=3, delta=0.1, strict=TRUE
      {200, 0.3, 1.5, 0.01, Alternative::two_sided, false, 0.590570981039644},  // sig.level=0.01
  };
  for (const auto& c : cases)
    EXPECT_NEAR(power_paired_t(c.n, c.delta, c.sd, c.alpha, c.alt, c.strict), c.power, 1e-9) << c.n << " " << c.delta;
  // power.t.test(delta=1, sd=1, power=0.9, type="paired")$n -> 12.5854745488964 (uniroot, tol 1.2e-4)
  // power.t.test(delta=0.5, sd=1, power=0.8, type="paired", tol=1e-12)$n -> 33.3672039788038
  EXPECT_NEAR(n_for_power_paired_t(1, 1, 0.9), 12.5854745488964, 2e-4);
  EXPECT_NEAR(n_for_power_paired_t(0.5, 1, 0.8), 33.3672039788038, 1e-6);
  EXPECT_EQ(smallest_n([](double n) { return power_paired_t(n, 0.5, 1); }, 0.8), 34);
  EXPECT_EQ(smallest_n([](double n) { return power_paired_t(n, 1, 1); }, 0.9), 13);
  EXPECT_TRUE(std::isnan(smallest_n([](double) { return 0.5; }, 0.8)));
}

// A published G*Power example: the G*Power 3.1 manual, "t test: Means - difference between two dependent
// means (matched pairs)", replicating Cohen (1969, p. 48): 50 IQ-matched pairs, d = 0.4 between two
// independent means, correlation 0.55 between the pairs, so d_z = 0.4 / sqrt(2 (1 - 0.55)) = 0.421637;
// two-sided alpha = .05: G*Power prints power 0.832114 (Cohen's table: 0.84).
// R 4.2.2: power.t.test(n = 50, delta = 0.4 / sqrt(2 * (1 - 0.55)), sd = 1, type = "paired", strict = TRUE)$power
//   -> 0.832114498894766 (G*Power counts both tails, as strict = TRUE)
TEST(Power, PairedTAsTheGPowerManualExample) {
  const double dz = 0.4 / std::sqrt(2 * (1 - 0.55));
  EXPECT_NEAR(dz, 0.421637, 1e-6);
  EXPECT_NEAR(power_paired_t(50, dz, 1, 0.05, Alternative::two_sided, true), 0.832114, 1e-6);
  EXPECT_NEAR(power_paired_t(50, dz, 1, 0.05, Alternative::two_sided, true), 0.832114498894766, 1e-9);
  // The same test as a 1-df repeated-measures effect: F = t^2, lambda = n d_z^2, df (1, n - 1).
  // R 4.2.2: pf(qf(0.95, 1, 49), 1, 49, ncp = 50 * 0.4^2 / (2 * 0.45), lower.tail = FALSE) -> 0.832114498894766
  EXPECT_NEAR(power_noncentral_f(50 * dz * dz, 1, 49), 0.832114498894766, 1e-9);
}

// G*Power's "ANOVA: Repeated measures, within factors": lambda = f^2 n m eps / (1 - rho),
// df1 = (m - 1) eps, df2 = (n - 1) df1. Reference: R 4.2.2
//   pf(qf(1 - alpha, df1, df2), df1, df2, ncp = lambda, lower.tail = FALSE)
// and pingouin's power_rm_anova documentation (tested there against G*Power), printed values in the comments.
TEST(Power, RepeatedMeasuresWithinAsGPower) {
  // pingouin: power_rm_anova(eta_squared=0.1, m=3, n=20) -> 0.8913; R: 0.891302707806556
  EXPECT_NEAR(power_rm_within(std::sqrt(0.1 / 0.9), 20, 3, 0.5), 0.891302707806556, 1e-9);
  // pingouin: power_rm_anova(eta_squared=0.346, m=4, n=9, epsilon=0.694) -> 0.99; R: 0.990322087009838
  EXPECT_NEAR(power_rm_within(std::sqrt(0.346 / 0.654), 9, 4, 0.5, 0.694), 0.990322087009838, 1e-9);
  // pingouin: same with corr=-0.1996 -> 0.771; R: 0.770843112495945
  EXPECT_NEAR(power_rm_within(std::sqrt(0.346 / 0.654), 9, 4, -0.1996, 0.694), 0.770843112495945, 1e-9);
  // R: f = 0.25, n = 28, m = 3, rho = 0.5 -> 0.812454611232873; f = 0.25, n = 12, m = 4, rho = 0.3, eps = 0.6 -> 0.25812217543583
  EXPECT_NEAR(power_rm_within(0.25, 28, 3, 0.5), 0.812454611232873, 1e-9);
  EXPECT_NEAR(power_rm_within(0.25, 12, 4, 0.3, 0.6), 0.25812217543583, 1e-9);
}

// The observed-effect power is the noncentral-F power with lambda = F df1 n / N (and epsilon).
TEST(Power, OfAnObservedEffectScalesLambdaWithN) {
  const RmAnovaResult r = *rm_anova(md());
  const Effect& angle = r.effects[1];
  ASSERT_EQ(angle.name, "angle");
  const double eps = angle.gg_epsilon;
  // At the pilot's own n: lambda = F df1 eps, df (2 eps, 18 eps).
  EXPECT_NEAR(power_of_effect(angle, 10, 10), power_noncentral_f(angle.F * 2 * eps, 2 * eps, 18 * eps), 1e-14);
  EXPECT_NEAR(power_of_effect(angle, 10, 20), power_noncentral_f(angle.F * 4 * eps, 2 * eps, 38 * eps), 1e-14);
  EXPECT_GT(power_of_effect(angle, 10, 20), power_of_effect(angle, 10, 10));
}

// Resampling participants of a large pilot drawn from a normal model converges
// to the analytic power of the pilot's observed effect: the Monte Carlo standard
// error of R = 2000 replications is sqrt(p (1 - p) / R) <= 0.0112, and the pilot
// of 4000 draws differs from a normal population by O(1/sqrt(4000)) in d_z; the
// tolerance is 4 MC SEs.
TEST(Power, ResamplingConvergesToTheAnalyticPower) {
  Random<SplitMix64> gen(20240501);  // dtlab\'s stream: the same data with every standard library
  const auto z = [](Random<SplitMix64>& g) { return g.normal(); };
  std::vector<std::vector<double>> pilot;
  for (int i = 0; i < 4000; ++i) {
    const double base = 10 + 2 * z(gen);
    pilot.push_back({base, base + 0.5 + z(gen)});  // difference ~ N(0.5, 1): d_z = 0.5
  }
  std::vector<double> x, y;
  for (const auto& row : pilot) {
    x.push_back(row[1]);
    y.push_back(row[0]);
  }
  const PairedTResult observed = paired_t(x, y);
  const std::size_t n = 20;
  const double analytic = power_paired_t(n, observed.mean_difference, observed.sd, 0.05, Alternative::two_sided, true);
  const auto test = [](const std::vector<std::vector<double>>& rows) {
    std::vector<double> a, b;
    for (const auto& r : rows) {
      a.push_back(r[1]);
      b.push_back(r[0]);
    }
    return paired_t(a, b).p;
  };
  const ResampledPower sim = power_by_resampling(pilot, n, test, 2000, 7);
  EXPECT_EQ(sim.replications, 2000u);
  EXPECT_NEAR(sim.power, analytic, 4 * std::sqrt(analytic * (1 - analytic) / 2000)) << "analytic " << analytic;
  EXPECT_LE(sim.ci_low, sim.power);
  EXPECT_GE(sim.ci_high, sim.power);
  const ResampledPower again = power_by_resampling(pilot, n, test, 2000, 7);
  EXPECT_EQ(again.rejections, sim.rejections) << "seeded: reproducible";
}

// Several hypotheses at once, on several threads: the same numbers for 1 and 2 threads (each replication
// has its own stream), and the one-hypothesis overload is the same computation.
TEST(Power, ResamplingIsTheSameOnAnyNumberOfThreads) {
  Random<SplitMix64> gen(11);  // dtlab\'s stream: the same data with every standard library
  const auto z = [](Random<SplitMix64>& g) { return g.normal(); };
  std::vector<std::vector<double>> pilot;
  for (int i = 0; i < 30; ++i) {
    const double base = z(gen);
    pilot.push_back({base, base + 0.4 + z(gen), base + 0.8 + z(gen)});
  }
  const ResampleTest test = [&](const std::vector<std::size_t>& draw) {
    std::vector<double> a, b, c;
    for (std::size_t i : draw) {
      a.push_back(pilot[i][0]);
      b.push_back(pilot[i][1]);
      c.push_back(pilot[i][2]);
    }
    return std::vector<double>{paired_t(b, a).p, paired_t(c, a).p};
  };
  const auto one = power_by_resampling(pilot.size(), 12, 2, test, 400, 99, 0.05, 1);
  const auto two = power_by_resampling(pilot.size(), 12, 2, test, 400, 99, 0.05, 2);
  ASSERT_EQ(one.size(), 2u);
  for (std::size_t h = 0; h < 2; ++h) {
    EXPECT_EQ(one[h].rejections, two[h].rejections) << h;
    EXPECT_EQ(one[h].replications, 400u);
    EXPECT_GE(one[h].power, one[h].ci_low);
    EXPECT_LE(one[h].power, one[h].ci_high);
  }
  EXPECT_GT(one[1].power, one[0].power) << "the larger difference is found more often";
  const auto other_seed = power_by_resampling(pilot.size(), 12, 2, test, 400, 100, 0.05, 2);
  EXPECT_NE(other_seed[0].rejections * 1000 + other_seed[1].rejections, one[0].rejections * 1000 + one[1].rejections);
  // Every or no replication rejecting: power 1 or 0 with the Wilson bound exactly 1 or 0, the other inside.
  const ResampleTest always = [](const std::vector<std::size_t>&) { return std::vector<double>{0.0, 1.0}; };
  const auto ends = power_by_resampling(5, 3, 2, always, 50, 1, 0.05, 2);
  EXPECT_EQ(ends[0].power, 1.0);
  EXPECT_EQ(ends[0].ci_high, 1.0);
  EXPECT_LT(ends[0].ci_low, 1.0);
  EXPECT_EQ(ends[1].power, 0.0);
  EXPECT_EQ(ends[1].ci_low, 0.0);
  EXPECT_GT(ends[1].ci_high, 0.0);
  // Degenerate inputs: no participant or no replication gives NaN power, never a division by zero.
  EXPECT_TRUE(std::isnan(power_by_resampling(0, 12, 1, test, 10, 1).front().power));
  EXPECT_TRUE(std::isnan(power_by_resampling(5, 12, 1, test, 0, 1).front().power));
}

// A three-level within effect: resampling a large pilot drawn from a normal model with compound symmetry
// (sphericity holds, so the uncorrected F test is exact) converges to the analytic noncentral-F power of
// the pilot's observed effect, lambda = F df1 n / N. Tolerance: 4 Monte Carlo SEs of R = 1000 replications.
TEST(Power, ResamplingAThreeLevelEffectConvergesToTheNoncentralF) {
  Random<SplitMix64> gen(20261202);  // dtlab\'s stream: the same data with every standard library
  const auto z = [](Random<SplitMix64>& g) { return g.normal(); };
  const std::size_t N = 3000;
  std::vector<std::vector<double>> pilot;
  for (std::size_t i = 0; i < N; ++i) {
    const double base = 5 * z(gen);
    pilot.push_back({base + z(gen), base + 0.5 + z(gen), base + 0.9 + z(gen)});
  }
  const auto anova_of = [&](const std::vector<std::size_t>& rows) {
    LongData d;
    d.within.push_back({"level", {}});
    std::vector<double> y;
    for (std::size_t k = 0; k < rows.size(); ++k)
      for (std::size_t c = 0; c < 3; ++c) {
        d.subject.push_back("s" + std::to_string(k));
        d.within[0].level.push_back("c" + std::to_string(c));
        y.push_back(pilot[rows[k]][c]);
      }
    d.dv = Measurements::from_doubles(std::move(y));
    return rm_anova(d);
  };
  std::vector<std::size_t> everyone(N);
  for (std::size_t i = 0; i < N; ++i) everyone[i] = i;
  const auto observed = anova_of(everyone);
  ASSERT_TRUE(observed.ok());
  const Effect& e = observed->effects.front();
  const std::size_t n = 15;
  const double analytic = power_noncentral_f(e.F * e.df1 * n / N, 2, 2 * (n - 1.0));
  const ResampleTest test = [&](const std::vector<std::size_t>& draw) {
    const auto r = anova_of(draw);
    return std::vector<double>{r ? r->effects.front().p : std::nan("")};
  };
  const auto sim = power_by_resampling(N, n, 1, test, 1000, 3, 0.05, 2).front();
  EXPECT_NEAR(sim.power, analytic, 4 * std::sqrt(analytic * (1 - analytic) / 1000)) << "analytic " << analytic;
  EXPECT_GT(analytic, 0.3);
  EXPECT_LT(analytic, 0.9);
}

// Post-hoc rows carry mean difference, SE, CI, t, df, p, Holm p and d_z.
// R 4.2.2, a, b, c as below:
//   pairwise.t.test(c(a, b, c), rep(c("a","b","c"), each = 10), paired = TRUE, p.adjust.method = "holm")$p.value
//     -> b-a 0.00849867059215281, c-a 0.02369870191360855, c-b 0.0342018954536123
//   t.test(a, b, paired = TRUE): estimate -1.58, stderr 0.388958723888395, conf.int -2.45988576327698 -0.700114236723018,
//     t -4.06212768338204, p 0.00283289019738427; mean(a - b) / sd(a - b) = -1.28455756259105
TEST(Posthoc, RowsCarryTheDifferenceItsCiAndHolmAsR) {
  std::string csv = "id,cond,y\n";
  const double a[] = {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
  const double b[] = {1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};
  const double c[] = {1.0, 0.5, 0.2, 0.3, 0.9, 3.0, 4.1, 1.2, 2.2, 2.5};
  char line[128];
  for (int i = 0; i < 10; ++i) {
    std::snprintf(line, sizeof line, "%d,a,%.1f\n%d,b,%.1f\n%d,c,%.1f\n", i, a[i], i, b[i], i, c[i]);
    csv += line;
  }
  auto r = pairwise_within(test::long_from_text(csv, {"y", "id", {"cond"}, {}}), "cond", PairwiseTest::paired_t);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->size(), 3u);
  const Comparison& ab = (*r)[0];
  EXPECT_EQ(ab.n, 10u);
  EXPECT_TRUE(near_rel(ab.estimate, -1.58, 1e-13));
  EXPECT_TRUE(near_rel(ab.se, 0.388958723888395, 1e-12));
  EXPECT_TRUE(near_rel(ab.ci_low, -2.45988576327698, 1e-12));
  EXPECT_TRUE(near_rel(ab.ci_high, -0.700114236723018, 1e-12));
  EXPECT_TRUE(near_rel(ab.statistic, -4.06212768338204, 1e-12));
  EXPECT_TRUE(near_rel(ab.p, 0.00283289019738427, 1e-10));
  EXPECT_TRUE(near_rel(ab.dz, -1.28455756259105, 1e-12));
  EXPECT_TRUE(near_rel(ab.p_holm, 0.00849867059215281, 1e-10));
  EXPECT_TRUE(near_rel((*r)[1].p_holm, 0.02369870191360855, 1e-10));
  EXPECT_TRUE(near_rel((*r)[2].p_holm, 0.0342018954536123, 1e-10));
}

}  // namespace
}  // namespace dtlab::stats
