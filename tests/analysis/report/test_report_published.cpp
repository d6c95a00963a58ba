// The report's numbers against published analyses of the same data: study
// databases whose participant x condition means are published data sets
// (studies.h), run through write_report, checked in report.json. The call
// that produced each expected value is written above it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tests/analysis/report/studies.h"

namespace dtlab::report::testing {
namespace {

double num(const nlohmann::json& j) { return j.get<double>(); }

// Relative agreement to the digits a source prints.
void expect_rel(double actual, double expected, double rel) {
  EXPECT_NEAR(actual, expected, rel * std::fabs(expected)) << "expected " << expected;
}

class Statsmodels2x2 : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new TempDir;
    build_statsmodels_2x2(dir->file("s.sqlite"));
    report = new nlohmann::json(run_report(dir->file("s.sqlite"), dir->file("out")));
  }
  static void TearDownTestSuite() {
    delete report;
    delete dir;
  }
  static TempDir* dir;
  static nlohmann::json* report;
};
TempDir* Statsmodels2x2::dir = nullptr;
nlohmann::json* Statsmodels2x2::report = nullptr;

TEST_F(Statsmodels2x2, OverallTwoByTwoMatchesEzAnova) {
  // statsmodels test_anova_rm.py, reference values from R:
  //   ezANOVA(data, dv = DV, wid = id, within = .(A, B, D)) on all 96 rows.
  // A and D are tested against the subject x A (x D) marginal means, so they
  // equal the transparency x scenario ANOVA of the means over B (= over the 3 trials).
  const auto& t = find_test(*report, "completion_time", "overall");
  EXPECT_EQ(t.at("n"), 8);
  const auto& a = find_effect(t, "transparency");    // A: F(1, 7) = 8.7650709, p = .021087505
  EXPECT_EQ(num(a.at("df1")), 1);
  EXPECT_EQ(num(a.at("df2")), 7);
  expect_rel(num(a.at("F")), 8.7650709, 1e-7);
  expect_rel(num(a.at("p")), 0.021087505, 1e-7);
  const auto& d = find_effect(t, "scenario");        // D: F(1, 7) = 20.5076546, p = .002704428
  expect_rel(num(d.at("F")), 20.5076546, 1e-7);
  expect_rel(num(d.at("p")), 0.002704428, 1e-6);
  const auto& ad = find_effect(t, "transparency:scenario");  // A:D: F(1, 7) = 21.7593382, p = .002301792
  expect_rel(num(ad.at("F")), 21.7593382, 1e-7);
  expect_rel(num(ad.at("p")), 0.002301792, 1e-6);
  // Two levels: sphericity holds trivially.
  EXPECT_EQ(num(a.at("gg_epsilon")), 1);
  EXPECT_TRUE(a.at("mauchly_W").is_null());
}

// The significant transparency x scenario interaction (A:D above) is followed up. R 4.2.2 on the
// participant x condition means (A x D means over B):
//   d <- read.csv("statsmodels_anova_rm.csv"); m <- aggregate(DV ~ id + A + D, d, mean)
//   w <- function(a, dd) m$DV[m$A == a & m$D == dd]          (ordered by id; A a = off, D a = abstract)
//   t.test(w("a", dd), w("b", dd), paired = TRUE); mean(x) / sd(x) for d_z; p.adjust(p, "holm") per factor
TEST_F(Statsmodels2x2, SignificantInteractionGetsSimpleEffectsAsRPairedT) {
  const auto& t = find_test(*report, "completion_time", "overall");
  ASSERT_EQ(t.at("followups").size(), 1u);
  const auto& f = t.at("followups")[0];
  EXPECT_EQ(f.at("effect"), "transparency:scenario");
  const auto& rows = f.at("simple_effects");
  ASSERT_EQ(rows.size(), 4u);
  struct Expected {
    const char *factor, *at;
    double est, se, lo, hi, t, p, p_holm, dz;
  };
  const Expected ex[] = {
      // transparency at scenario = abstract: t.test(w("a","a"), w("b","a"), paired = TRUE)
      {"transparency", "abstract", -6, 0.947008657207207, -8.23931963730048, -3.76068036269952, -6.33573933494379,
       0.000390526338119925, 0.000781052676239851, -2.24002212378455},
      // at walkthrough: t.test(w("a","b"), w("b","b"), paired = TRUE)
      {"transparency", "walkthrough", -0.375, 1.46579722606386, -3.84105966866803, 3.09105966866804,
       -0.25583347637176, 0.80543441381912, 0.80543441381912, -0.0904507929984999},
      // scenario at transparency = off: t.test(w("a","a"), w("a","b"), paired = TRUE)
      {"scenario", "off", 1, 1.06159508617181, -1.51027348613359, 3.51027348613359, 0.941978738434139,
       0.377567540455956, 0.377567540455956, 0.333039776840164},
      // at on: t.test(w("b","a"), w("b","b"), paired = TRUE)
      {"scenario", "on", 6.625, 1.00876614087911, 4.2396471190916, 9.0103528809084, 6.56742899224049,
       0.000313680006667667, 0.000627360013335334, 2.32193678768719},
  };
  for (size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    const auto& r = rows[i];
    EXPECT_EQ(r.at("factor"), ex[i].factor);
    EXPECT_EQ(r.at("at_level"), ex[i].at);
    EXPECT_EQ(r.at("test"), "paired t");
    const auto& c = r.at("contrast");
    expect_rel(num(c.at("estimate")), ex[i].est, 1e-12);
    expect_rel(num(c.at("se")), ex[i].se, 1e-12);
    expect_rel(num(c.at("ci_low")), ex[i].lo, 1e-12);
    expect_rel(num(c.at("ci_high")), ex[i].hi, 1e-12);
    expect_rel(num(c.at("statistic")), ex[i].t, 1e-12);
    EXPECT_EQ(num(c.at("df")), 7);
    expect_rel(num(r.at("p")), ex[i].p, 1e-10);
    expect_rel(num(r.at("p_holm")), ex[i].p_holm, 1e-10);
    expect_rel(num(c.at("dz")), ex[i].dz, 1e-12);
  }
  // Cousineau-Morey 95% CIs, the formula of Morey (2008) in R:
  //   Y <- cbind(w("a","a"), w("a","b"), w("b","a"), w("b","b")); N <- 8; C <- 4
  //   Z <- Y - rowMeans(Y) + mean(Y); se <- apply(Z, 2, sd) / sqrt(N) * sqrt(C / (C - 1))
  //   colMeans(Y) -> 9 8 15 8.375; colMeans(Y) -/+ qt(0.975, N - 1) * se
  const auto& cells = f.at("cell_means_within_ci");
  ASSERT_EQ(cells.size(), 4u);
  const double mean[] = {9, 8, 15, 8.375};
  const double se[] = {0.534657798634053, 1.11276228998882, 0.885740487003648, 0.816483924322609};
  const double lo[] = {7.73573520304671, 5.36873530283451, 12.9055565638136, 6.44432231151111};
  const double hi[] = {10.2642647969533, 10.6312646971655, 17.0944434361864, 10.3056776884889};
  for (size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    expect_rel(num(cells[i].at("mean")), mean[i], 1e-13);
    expect_rel(num(cells[i].at("se_within")), se[i], 1e-12);
    expect_rel(num(cells[i].at("ci95_low")), lo[i], 1e-12);
    expect_rel(num(cells[i].at("ci95_high")), hi[i], 1e-12);
  }
  EXPECT_EQ(cells[1].at("levels").at("transparency"), "off");
  EXPECT_EQ(cells[1].at("levels").at("scenario"), "walkthrough");
  // tests.csv has a row per simple effect with the exact t, p and Holm p.
  const std::string csv = read_text(dir->file("out/tests.csv"));
  EXPECT_NE(csv.find("time,completion time,s,overall,simple effect (paired t),transparency at scenario = abstract,8,7,NA,"
                     "-6.33573933494"),
            std::string::npos);
  // One-factor tests have no interaction to follow up.
  EXPECT_FALSE(find_test(*report, "completion_time", "T1").contains("followups"));
}

// Every ANOVA row carries what a paper prints: MSE, the eta_p2 interval and an APA sentence.
// R 4.2.2: summary(aov(DV ~ A * D + Error(factor(id) / (A * D)), m)) -> A:D Residuals 7 20.3576388889 2.908234127
//   F <- 63.28125 / (20.3576388888889 / 7)
//   g <- function(t) uniroot(function(l) pf(F, 1, 7, ncp = l) - t, c(0, 10 * F + 100), tol = 1e-13)$root
//   l <- g(0.95); h <- g(0.05); l / (l + 9) -> 0.300447241267373; h / (h + 9) -> 0.850683725625452
TEST_F(Statsmodels2x2, AnovaRowsCarryMseAndAnApaSentence) {
  const auto& ad = find_effect(find_test(*report, "completion_time", "overall"), "transparency:scenario");
  expect_rel(num(ad.at("mse")), 2.90823412698413, 1e-12);
  expect_rel(num(ad.at("eta_p2")), 0.756600797077383, 1e-12);
  // R's pnbeta stops at an error of 1e-9 (errmax), so the bounds agree to about 1e-8.
  expect_rel(num(ad.at("eta_p2_ci90_low")), 0.300447241267373, 1e-8);
  expect_rel(num(ad.at("eta_p2_ci90_high")), 0.850683725625452, 1e-8);
  EXPECT_EQ(ad.at("apa"), "F(1, 7) = 21.76, p = .002, ηp² = .76, 90% CI [.30, .85]");
  // tests.csv holds the same sentence and the exact MSE.
  const std::string csv = read_text(dir->file("out/tests.csv"));
  EXPECT_NE(csv.find("F(1, 7) = 21.76, p = .002, ηp² = .76, 90% CI [.30, .85]"), std::string::npos);
}

// Assumptions and robustness of the completion-time ANOVAs, R 4.2.2 on the same means (m, w as above):
//   Y <- cbind(w("a","a"), w("a","b"), w("b","a"), w("b","b")); N <- 8; C <- 4
//   E <- Y - rowMeans(Y) - matrix(colMeans(Y), N, C, byrow = TRUE) + mean(Y)
//   shapiro.test(as.vector(t(E))) -> W = 0.9785979843233, p-value = 0.757904229139
//   T1 (D = a, transparency only): t1 <- aggregate(DV ~ id + A, subset(d, D == "a"), mean), E1 likewise
//   shapiro.test(as.vector(t(E1))) -> W = 0.9837808556494, p-value = 0.986457546127
//   wilcox.test((w("a","a") + w("a","b")) / 2, (w("b","a") + w("b","b")) / 2, paired = TRUE) -> V = 3, p = 0.0390625
//   wilcox.test((w("a","a") + w("b","a")) / 2, (w("a","b") + w("b","b")) / 2, paired = TRUE) -> V = 35, p = 0.015625
TEST_F(Statsmodels2x2, ResidualNormalityAndRankTestsPerFactorAsR) {
  const auto& overall = find_test(*report, "completion_time", "overall").at("shapiro_wilk_residuals");
  EXPECT_EQ(overall.at("n"), 32);
  expect_rel(num(overall.at("W")), 0.9785979843233, 1e-9);
  expect_rel(num(overall.at("p")), 0.757904229139, 1e-6);
  const auto& t1 = find_test(*report, "completion_time", "T1").at("shapiro_wilk_residuals");
  EXPECT_EQ(t1.at("n"), 16);
  expect_rel(num(t1.at("W")), 0.9837808556494, 1e-9);
  expect_rel(num(t1.at("p")), 0.986457546127, 1e-6);
  // Over all tasks each design factor gets its own rank test on its marginal means (never one 4-cell test).
  std::map<std::string, std::pair<double, double>> seen;  // factor -> (V, p)
  for (const auto& t : report->at("completion_time").at("rank_tests")) {
    ASSERT_EQ(t.at("test"), "wilcoxon") << t.at("scope");
    if (t.at("scope") == "overall")
      seen[t.at("factors")[0].get<std::string>()] = {num(t.at("wilcoxon").at("V")), num(t.at("wilcoxon").at("p"))};
  }
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen["transparency"].first, 3);
  expect_rel(seen["transparency"].second, 0.0390625, 1e-12);
  EXPECT_EQ(seen["scenario"].first, 35);
  expect_rel(seen["scenario"].second, 0.015625, 1e-12);
  const std::string csv = read_text(dir->file("out/tests.csv"));
  EXPECT_NE(csv.find("time,completion time,s,overall,shapiro-wilk,residuals,8,"), std::string::npos);
  EXPECT_NE(csv.find("time,completion time (ranks),s,overall,wilcoxon,scenario,8,NA,NA,35,"), std::string::npos);
}

// --log-time analyses the participants' mean log times beside the seconds. R 4.2.2:
//   m <- aggregate(log(DV) ~ id + A + D, d, mean); summary(aov(y ~ A * D + Error(factor(id) / (A * D)), m))
//   -> A F = 4.56659 p = 0.069948; D F = 26.84208 p = 0.0012796; A:D F = 3.53936 p = 0.10197
//   x <- on - off of the A marginal means; exp(mean(x)), exp(t.test(x)$conf.int)
//   -> ratio 1.33735998534624 [0.969504525675173, 1.84478946001798]
TEST(ReportPublished, LogTimeIsAnalysedBesideTheSecondsAsR) {
  TempDir dir;
  build_statsmodels_2x2(dir.file("s.sqlite"));
  ReportOptions options;
  options.log_time = true;
  const auto report = run_report(dir.file("s.sqlite"), dir.file("out"), options);
  const nlohmann::json* overall = nullptr;
  for (const auto& t : report.at("completion_time_log").at("tests"))
    if (t.at("scope") == "overall") overall = &t;
  ASSERT_NE(overall, nullptr);
  EXPECT_EQ(overall->at("measure"), "log completion time");
  expect_rel(num(find_effect(*overall, "transparency").at("F")), 4.56659, 1e-5);
  expect_rel(num(find_effect(*overall, "transparency").at("p")), 0.069948, 1e-4);
  expect_rel(num(find_effect(*overall, "scenario").at("F")), 26.84208, 1e-6);
  expect_rel(num(find_effect(*overall, "transparency:scenario").at("F")), 3.53936, 1e-5);
  EXPECT_FALSE(overall->contains("followups"));  // p = .10: not followed up
  const auto& paired = overall->at("paired");
  expect_rel(std::exp(num(paired.at("mean_difference"))), 1.33735998534624, 1e-12);
  expect_rel(std::exp(num(paired.at("ci_low"))), 0.969504525675173, 1e-12);
  expect_rel(std::exp(num(paired.at("ci_high"))), 1.84478946001798, 1e-12);
  // The seconds stay the primary analysis.
  expect_rel(num(find_effect(find_test(report, "completion_time", "overall"), "transparency").at("F")), 8.7650709, 1e-7);
  const std::string md = read_text(dir.file("out/report.md"));
  EXPECT_NE(md.find("Completion time on the log scale"), std::string::npos);
  EXPECT_NE(md.find("| All tasks | "), std::string::npos);
}

TEST_F(Statsmodels2x2, TableThreeRowsCarryTheOverallEffectAndTheArticle) {
  const auto& rows = report->at("completion_time").at("table");
  ASSERT_EQ(rows.size(), 5u);  // T1..T4 and all tasks
  EXPECT_EQ(rows[0].at("scope"), "T1");
  EXPECT_EQ(rows[4].at("scope"), "overall");
  expect_rel(num(rows[4].at("effect").at("F")), 8.7650709, 1e-7);
  // The article's Table III values, labelled as such (Elmqvist et al. 2008, Table III: T4 140.0 (61.75)).
  // The reference protocol declares them ([reference_results]); the report reads them from the recorded text.
  EXPECT_EQ(num(rows[3].at("published").at("mean").at("off")), 140.0);
  EXPECT_EQ(rows[3].at("published").at("F"), "48.61");
  EXPECT_EQ(rows[3].at("published").at("label"), "article");
  EXPECT_EQ(report->at("design").at("published_results"), "Elmqvist, Assarsson & Tsigas (2008)");
  EXPECT_TRUE(report->at("design").at("reference_design").get<bool>());
}

TEST_F(Statsmodels2x2, AccuracyMeasuresFollowTheirDefinitions) {
  // S1 (p = 0), T1 with transparency off: truths 25, 30, 35; answers 26, 30, 34.
  // Per-trial relative error: (1/25 + 0 + 1/35) / 3 = 0.0228571...; aggregated: |90 - 90| / 90 = 0.
  const std::string csv = read_text(dir->file("out") + "/accuracy_means.csv");
  EXPECT_NE(csv.find("rel_error_mean,T1,S1,off,abstract,0.022857142857142857,3\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("rel_error_aggregated,T1,S1,off,abstract,0,3\n"), std::string::npos);
  // S2 (p = 1): answers 27, 30, 34 -> aggregated |90 - 91| / 90.
  EXPECT_NE(csv.find("rel_error_aggregated,T1,S2,off,abstract,0.011111111111111112,3\n"), std::string::npos);
  // T2 correctness: S1..S4 miss the third letter with transparency off -> 2/3.
  EXPECT_NE(csv.find("proportion_correct,T2,S1,off,abstract,0.6666666666666666,3\n"), std::string::npos);
  EXPECT_NE(csv.find("proportion_correct,T2,S5,off,abstract,1,3\n"), std::string::npos);
  // T3 distance: answer (13, 14) for truth (10, 10) -> 5 world units.
  EXPECT_NE(csv.find("distance_mean,T3,S1,off,walkthrough,5,3\n"), std::string::npos);
  // Combined counting tasks T1+T4 exist as their own rows, and T2 is tested with Friedman.
  EXPECT_EQ(find_test(*report, "accuracy", "T1+T4", "relative error (aggregated)").at("test"), "rm-anova");
  EXPECT_EQ(find_test(*report, "accuracy", "T2").at("test"), "friedman");
}

TEST_F(Statsmodels2x2, RatingsByFriedmanPerScenarioAndOverall) {
  const auto& q = report->at("questionnaire").at("rating").at("tests");
  ASSERT_EQ(q.size(), 3u);  // abstract, walkthrough, overall
  auto by_scope = [&](const std::string& s) -> const nlohmann::json& {
    for (const auto& t : q)
      if (t.at("scope") == s) return t.at("friedman");
    throw std::runtime_error("no scope " + s);
  };
  // Every participant rates on above off: Q = n = 8, df = 1.
  // R: friedman.test(...) -> Friedman chi-squared = 8; pchisq(8, 1, lower.tail = FALSE) = 0.004677735
  EXPECT_DOUBLE_EQ(num(by_scope("abstract").at("Q")), 8);
  expect_rel(num(by_scope("abstract").at("p")), 0.004677735, 1e-6);
  // Walkthrough: 6 on above off, 2 below: Q = (6 - 2)^2 / 8 = 2; pchisq(2, 1, lower.tail = FALSE) = 0.1572992
  EXPECT_DOUBLE_EQ(num(by_scope("walkthrough").at("Q")), 2);
  expect_rel(num(by_scope("walkthrough").at("p")), 0.1572992, 1e-6);
  // Overall means (on 3 or 2, off 1.5): all on above off again.
  EXPECT_DOUBLE_EQ(num(by_scope("overall").at("Q")), 8);
  // Preference 7 of 8 for "on", one neutral: R binom.test(7, 7)$p.value = 0.015625
  const auto& pref = report->at("questionnaire").at("preference");
  EXPECT_EQ(pref.at("choices").at("on").at("count"), 7);
  EXPECT_DOUBLE_EQ(num(pref.at("sign_test").at("p")), 0.015625);
  // Depth test: 7 x 3 + 2 pairs over 8 participants = 2.875 of 3.
  EXPECT_DOUBLE_EQ(num(report->at("questionnaire").at("depth_test").at("descriptives").at("mean")), 2.875);
}

TEST(ReportPublished, TaskRowMatchesEzAnovaAndPairedT) {
  TempDir dir;
  build_statsmodels_t1(dir.file("s.sqlite"));
  const auto report = run_report(dir.file("s.sqlite"), dir.file("out"));
  const auto& t = find_test(report, "completion_time", "T1");
  // statsmodels test_anova_rm.py, rows 1-16 (B within, 8 subjects), R: ezANOVA(...) F(1, 7) = 22.4, p = 0.002125452
  const auto& e = find_effect(t, "transparency");
  expect_rel(num(e.at("F")), 22.4, 1e-9);
  expect_rel(num(e.at("p")), 0.002125452, 1e-6);
  // R: t.test(on, off, paired = TRUE): differences 0 8 3 5 5 2 5 4, mean 4, sd sqrt(40/7),
  // 95% CI 4 -+ qt(0.975, 7) * sd / sqrt(8) = [2.001528, 5.998472]; t^2 = F.
  const auto& pd = t.at("paired");
  EXPECT_DOUBLE_EQ(num(pd.at("mean_difference")), 4.0);
  EXPECT_NEAR(num(pd.at("ci_low")), 2.001528, 1e-6);
  EXPECT_NEAR(num(pd.at("ci_high")), 5.998472, 1e-6);
  EXPECT_NEAR(num(pd.at("t")) * num(pd.at("t")), 22.4, 1e-9);
}

TEST(ReportPublished, OneFactorFourLevelsWithMissingCellsMatchesPingouin) {
  TempDir dir;
  build_pingouin_wide(dir.file("s.sqlite"));
  const auto report = run_report(dir.file("s.sqlite"), dir.file("out"));
  const auto& t = find_test(report, "completion_time", "T1");
  // pingouin tests (compared there with JAMOVI / ezANOVA): pg.rm_anova(rm_anova_wide) with listwise
  // deletion, 9 of 12 subjects: F = 5.20065, p = 0.00656, np2 = 0.39397, ng2 = 0.34639,
  // GG epsilon = 0.69433, Mauchly W = 0.30678, p_GG = 0.01670.
  EXPECT_EQ(t.at("n"), 9);
  const auto& e = find_effect(t, "week");
  EXPECT_EQ(num(e.at("df1")), 3);
  EXPECT_EQ(num(e.at("df2")), 24);
  expect_rel(num(e.at("F")), 5.20065, 1e-5);
  expect_rel(num(e.at("p")), 0.00656, 1e-3);
  expect_rel(num(e.at("eta_p2")), 0.39397, 1e-4);
  expect_rel(num(e.at("eta_g2")), 0.34639, 1e-4);
  expect_rel(num(e.at("gg_epsilon")), 0.69433, 1e-4);
  expect_rel(num(e.at("mauchly_W")), 0.30678, 1e-4);
  expect_rel(num(e.at("p_gg")), 0.01670, 1e-3);
  // The excluded participants are named with their missing cells.
  const auto& ex = t.at("excluded");
  ASSERT_EQ(ex.size(), 3u);
  EXPECT_EQ(ex[0], "W03 (week3: no trial)");
  EXPECT_EQ(ex[1], "W11 (before: no trial)");
  EXPECT_EQ(ex[2], "W07 (week2: no trial, week3: no trial)");
  // Holm post-hoc for a four-level factor: 6 pairs, Holm p never below the raw p.
  const auto& ph = t.at("posthoc").at("week");
  ASSERT_EQ(ph.size(), 6u);
  for (const auto& c : ph) {
    EXPECT_GE(num(c.at("p_holm")), num(c.at("p")));
    // Each row also has the paired difference's SE, 95% CI and d_z (values checked in test_stats against R).
    EXPECT_LT(num(c.at("ci_low")), num(c.at("estimate")));
    EXPECT_GT(num(c.at("ci_high")), num(c.at("estimate")));
    EXPECT_NEAR(num(c.at("statistic")), num(c.at("estimate")) / num(c.at("se")), 1e-9 * std::fabs(num(c.at("statistic"))));
    EXPECT_FALSE(c.at("dz").is_null());
  }
  // Incomplete sessions are reported as such.
  bool warned = false;
  for (const auto& w : report.at("warnings")) warned = warned || w.get<std::string>().rfind("W07: session running", 0) == 0;
  EXPECT_TRUE(warned);
}

TEST(ReportPublished, OneFactorThreeLevelsMatchesPingouinAndFriedmanMatchesR) {
  TempDir dir;
  build_pingouin_months(dir.file("s.sqlite"));
  const auto report = run_report(dir.file("s.sqlite"), dir.file("out"));
  const auto& t = find_test(report, "completion_time", "T1");
  // pingouin tests: pg.rm_anova(dv='Scores', within='Time', subject='Subject', data=mixed_anova):
  // F = 3.91280, p = 0.02263, ng2 = 0.03998, np2 = 0.06219; Mauchly W = 0.999 (test_distribution).
  EXPECT_EQ(t.at("n"), 60);
  const auto& e = find_effect(t, "month");
  expect_rel(num(e.at("F")), 3.91280, 1e-5);
  expect_rel(num(e.at("p")), 0.02263, 1e-3);
  expect_rel(num(e.at("eta_g2")), 0.03998, 1e-3);
  expect_rel(num(e.at("eta_p2")), 0.06219, 1e-3);
  EXPECT_NEAR(num(e.at("mauchly_W")), 0.999, 5e-4);
  EXPECT_FALSE(e.at("p_hf").is_null());
  EXPECT_EQ(t.at("posthoc").at("month").size(), 3u);
  // R: friedman.test(RoundingTimes): Friedman chi-squared = 11.143, df = 2, p-value = 0.003805
  const auto& q = report.at("questionnaire").at("speed").at("tests");
  ASSERT_EQ(q.size(), 1u);
  const auto& f = q[0].at("friedman");
  EXPECT_EQ(f.at("n"), 22);
  expect_rel(num(f.at("Q")), 11.143, 1e-4);
  expect_rel(num(f.at("p")), 0.003805, 1e-3);
  // The entry holds the fields `dtlab stats friedman --json` prints (stats/json.h), the Iman-Davenport test
  // among them. R (r/friedman_iman_davenport.R): Q <- unname(friedman.test(RoundingTimes)$statistic);
  // F <- 21 * Q / (22 * 2 - Q) = 7.12173913043478; pf(F, 2, 42, lower.tail = FALSE) = 0.00217129838761;
  // rows 7, 15, 17 and 22 hold ties.
  EXPECT_EQ(num(f.at("iman_davenport_df1")), 2);
  EXPECT_EQ(num(f.at("iman_davenport_df2")), 42);
  expect_rel(num(f.at("iman_davenport_F")), 7.12173913043478, 1e-10);
  expect_rel(num(f.at("p_iman_davenport")), 0.00217129838761, 1e-9);
  EXPECT_TRUE(f.at("ties").get<bool>());
  EXPECT_EQ(q[0].at("posthoc").at("month").size(), 3u);
}

}  // namespace
}  // namespace dtlab::report::testing
