// Friedman test against R's friedman.test examples, scipy's test values,
// exact conditional p-values and the exact null tables (exact rational
// arithmetic, cross-checked with R package SuppDists), plus hard cases.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/stats/detail/friedman_exact.h"
#include "analysis/stats/friedman.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

// Treatments given as columns (scipy's layout) -> blocks x treatments.
std::vector<std::vector<double>> blocks_from_columns(const std::vector<std::vector<double>>& cols) {
  std::vector<std::vector<double>> y(cols.front().size(), std::vector<double>(cols.size()));
  for (size_t j = 0; j < cols.size(); ++j)
    for (size_t i = 0; i < cols[j].size(); ++i) y[i][j] = cols[j][i];
  return y;
}

// R 4.x stats-Ex.Rout.save: RoundingTimes (Hollander & Wolfe 1973, p. 140ff.), 22 x 3.
const std::vector<std::vector<double>> kRoundingTimes{
    {5.40, 5.50, 5.55}, {5.85, 5.70, 5.75}, {5.20, 5.60, 5.50}, {5.55, 5.50, 5.40}, {5.90, 5.85, 5.70},
    {5.45, 5.55, 5.60}, {5.40, 5.40, 5.35}, {5.45, 5.50, 5.35}, {5.25, 5.15, 5.00}, {5.85, 5.80, 5.70},
    {5.25, 5.20, 5.10}, {5.65, 5.55, 5.45}, {5.60, 5.35, 5.45}, {5.05, 5.00, 4.95}, {5.50, 5.50, 5.40},
    {5.45, 5.55, 5.50}, {5.55, 5.55, 5.35}, {5.45, 5.50, 5.55}, {5.50, 5.45, 5.25}, {5.65, 5.60, 5.40},
    {5.70, 5.65, 5.55}, {6.30, 6.30, 6.25}};

struct Case {
  const char* what;
  std::vector<std::vector<double>> y;  // blocks x treatments
  const char* Q;                       // as printed by the source
  const char* p;
  const char* p_exact;                 // exact conditional p (reference folder), as printed
  const char* p_id;                    // Iman-Davenport p (reference folder), as printed
};

std::vector<Case> cases() {
  return {
      // R: friedman.test(RoundingTimes) -> Friedman chi-squared = 11.143, df = 2, p-value = 0.003805
      // reference folder: Q=11.14285714 p_chi2=0.00380504 p_exact_cond=0.00314983 p_ImanDavenportF=0.0021713
      {"R RoundingTimes", kRoundingTimes, "11.14285714", "0.00380504", "0.00314983", "0.0021713"},
      // scipy: stats.friedmanchisquare(*x1) == (10.2283464566929, 0.0167215803284414) (Demsar 2006)
      {"scipy Demsar", blocks_from_columns({{0.763, 0.599, 0.954, 0.628, 0.882, 0.936, 0.661, 0.583, 0.775, 1.0, 0.94, 0.619, 0.972, 0.957},
                                            {0.768, 0.591, 0.971, 0.661, 0.888, 0.931, 0.668, 0.583, 0.838, 1.0, 0.962, 0.666, 0.981, 0.978},
                                            {0.771, 0.59, 0.968, 0.654, 0.886, 0.916, 0.609, 0.563, 0.866, 1.0, 0.965, 0.614, 0.9751, 0.946},
                                            {0.798, 0.569, 0.967, 0.657, 0.898, 0.931, 0.685, 0.625, 0.875, 1.0, 0.962, 0.669, 0.975, 0.97}}),
       "10.2283464566929", "0.0167215803284414", "0.0135929", "0.0116207"},
      // scipy: stats.friedmanchisquare(*x2) == (18.9428571428571, 0.000280938375189499) ("Bioestadistica")
      {"scipy Bioestadistica", blocks_from_columns({{4, 3, 5, 3, 5, 3, 2, 5, 4, 4, 4, 3}, {2, 2, 1, 2, 3, 1, 2, 3, 2, 1, 1, 3},
                                                    {2, 4, 3, 3, 4, 3, 3, 4, 4, 1, 2, 1}, {3, 5, 4, 3, 4, 4, 3, 3, 3, 4, 4, 4}}),
       "18.9428571428571", "0.000280938375189499", "5.34625e-05", "1.54771e-05"},
      // scipy: stats.friedmanchisquare(*x3) == (10.68, 0.0135882729582176) (Zar, example 12.6)
      {"scipy Zar 12.6", blocks_from_columns({{7.0, 9.9, 8.5, 5.1, 10.3}, {5.3, 5.7, 4.7, 3.5, 7.7}, {4.9, 7.6, 5.5, 2.8, 8.4},
                                              {8.8, 8.9, 8.1, 3.3, 9.1}}),
       "10.68", "0.0135882729582176", "0.0054585", "0.00145188"},
  };
}

TEST(Friedman, MatchesRScipyAndExactConditionalP) {
  for (const auto& c : cases()) {
    SCOPED_TRACE(c.what);
    const FriedmanResult r = friedman_blocks(c.y);
    EXPECT_TRUE(printed(r.Q, c.Q));
    EXPECT_TRUE(near_rel(r.p, std::strtod(c.p, nullptr), std::string(c.p).size() > 12 ? 1e-12 : 1e-5));
    EXPECT_EQ(r.df, static_cast<double>(c.y.front().size() - 1));
    EXPECT_EQ(r.exact_method, "exact");
    EXPECT_TRUE(printed(r.p_exact, c.p_exact));
    EXPECT_TRUE(near_rel(r.p_iman_davenport, std::strtod(c.p_id, nullptr), 5e-5));
    EXPECT_DOUBLE_EQ(r.kendall_W, r.Q / (r.n * (r.k - 1.0)));
  }
}

TEST(Friedman, RWarpbreaksExampleTwoTreatments) {
  // R: wb <- aggregate(warpbreaks$breaks, by = list(w = wool, t = tension), FUN = mean)
  //    friedman.test(wb$x, wb$w, wb$t) -> Friedman chi-squared = 0.33333, df = 1, p-value = 0.5637
  // blocks = tension L, M, H; treatments = wool A, B (means 401/9, 254/9 | 216/9, 259/9 | 221/9, 169/9)
  const FriedmanResult r = friedman_blocks({{401.0 / 9, 254.0 / 9}, {216.0 / 9, 259.0 / 9}, {221.0 / 9, 169.0 / 9}});
  EXPECT_TRUE(printed(r.Q, "0.33333"));
  EXPECT_TRUE(printed(r.p, "0.5637"));
}

// Exact null distribution of Q for untied data against the tables in the
// reference folder: every listed Q of every (k, n) in the table.
TEST(Friedman, ExactDistributionMatchesTheNullTables) {
  std::ifstream in(test::data_path("friedman_exact_null_tables.txt"));
  ASSERT_TRUE(in.good());
  std::map<std::pair<int, int>, std::vector<std::pair<double, double>>> table;  // (k, n) -> (Q, P(Q' >= Q))
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    int k, n;
    double q, count, p_float, chi;
    std::string frac;
    ss >> k >> n >> q >> count >> frac >> p_float >> chi;
    const size_t slash = frac.find('/');
    const double p = std::strtod(frac.substr(0, slash).c_str(), nullptr) / std::strtod(frac.substr(slash + 1).c_str(), nullptr);
    table[{k, n}].push_back({q, p});
  }
  ASSERT_GE(table.size(), 30u);
  size_t checked = 0;
  for (const auto& [kn, rows] : table) {
    const auto [k, n] = kn;
    SCOPED_TRACE("k=" + std::to_string(k) + " n=" + std::to_string(n));
    std::vector<std::vector<int>> ranks(n, std::vector<int>(k));
    for (auto& row : ranks)
      for (int j = 0; j < k; ++j) row[j] = 2 * (j + 1);
    const auto dist = detail::friedman_exact_distribution(ranks, 1e9);
    ASSERT_TRUE(dist.has_value());
    for (const auto& [q, p] : rows) {
      // Q = 12 S_r / (n k (k+1)) with S_r = sum (R_j - n(k+1)/2)^2; doubled ranks: S = 4 sum R_j^2.
      const double sum_r2 = q * n * k * (k + 1) / 12.0 + n * n * k * (k + 1.0) * (k + 1.0) / 4.0;
      const auto s_obs = static_cast<std::int64_t>(std::llround(4.0 * sum_r2));
      double tail = 0.0;
      for (const auto& [s, prob] : *dist)
        if (s >= s_obs) tail += prob;
      EXPECT_TRUE(near_rel(tail, p, 1e-12)) << "Q=" << q;
      ++checked;
    }
  }
  EXPECT_GT(checked, 2500u);
}

// s_obs (doubled ranks: 4 sum R_j^2) of an untied design's Q.
std::int64_t doubled_s(double q, int k, int n) {
  const double sum_r2 = q * n * k * (k + 1) / 12.0 + n * n * k * (k + 1.0) * (k + 1.0) / 4.0;
  return static_cast<std::int64_t>(std::llround(4.0 * sum_r2));
}

std::vector<std::vector<int>> untied(int k, int n) {
  std::vector<std::vector<int>> ranks(n, std::vector<int>(k));
  for (auto& row : ranks)
    for (int j = 0; j < k; ++j) row[j] = 2 * (j + 1);
  return ranks;
}

// Exact critical values (k = 3..6, n up to 15, 10, 8 and 5; beyond the null
// tables for k = 3..5): the tail at each Q_crit is the listed exact size.
TEST(Friedman, ExactTailsAtTheCriticalValues) {
  std::ifstream in(test::data_path("friedman_exact_critical_values.txt"));
  ASSERT_TRUE(in.good());
  std::string line;
  size_t checked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    int k, n;
    double alpha, q, size;
    ss >> k >> n >> alpha >> q >> size;
    const auto tail = detail::friedman_exact_tail(untied(k, n), doubled_s(q, k, n), 1e10);
    ASSERT_TRUE(tail.has_value()) << line;
    EXPECT_TRUE(printed(*tail, [&] {
      std::ostringstream t;
      t << size;
      return t.str();
    }())) << line;
    EXPECT_LE(*tail, alpha) << line;
    ++checked;
  }
  EXPECT_GT(checked, 120u);
}

// Broke: --exact always at k = 6, n = 12 took about 280 s (a hash map of
// sorted rank-sum vectors over 720 arrangements per block); now 1.5-3.5 s of
// CPU. The whole distribution against integer counts from an independent
// program (data/friedman_exact_counts.cpp): every attainable S of k = 6, n = 12.
TEST(Friedman, ExactDistributionKSixNTwelveMatchesIntegerCounts) {
  std::ifstream in(test::data_path("friedman_exact_k6_n12.txt"));
  ASSERT_TRUE(in.good());
  const auto dist = detail::friedman_exact_distribution(untied(6, 12), 3e9);
  ASSERT_TRUE(dist.has_value());
  std::map<std::int64_t, double> tail;  // P(S' >= S), S of the undoubled ranks
  double above = 0;
  for (auto it = dist->rbegin(); it != dist->rend(); ++it) tail[it->first / 4] = (above += it->second);
  std::string line;
  size_t checked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    long long s;
    double q;
    std::string count, tail_count, total;
    ss >> s >> q >> count >> tail_count >> total;
    // counts up to 1.9e34: their ratio in long double is exact to far below the tolerance
    const double expected = static_cast<double>(std::strtold(tail_count.c_str(), nullptr) / std::strtold(total.c_str(), nullptr));
    ASSERT_EQ(tail.count(s), 1u) << "S = " << s << " attainable in the reference";
    EXPECT_TRUE(near_rel(tail[s], expected, 1e-12)) << "S = " << s;
    ++checked;
  }
  EXPECT_EQ(checked, dist->size());
  EXPECT_EQ(checked, 1233u);
}

// The same through friedman() on data: --exact always at k = 6, n = 12
// (untied blocks, Q = 6.047619048): tail_count / total =
// 5984015105972443171753432509655680 / 19408409961765342806016000000000000.
TEST(Friedman, ExactAlwaysComputesKSixNTwelve) {
  const std::vector<std::vector<double>> y{
      {79, 32, 94, 45, 88, 83}, {67, 6, 65, 108, 43, 98}, {6, 20, 14, 47, 60, 31}, {48, 72, 19, 82, 43, 16},
      {93, 27, 52, 35, 23, 98}, {49, 23, 103, 18, 29, 94}, {79, 56, 16, 0, 26, 99}, {27, 24, 43, 49, 37, 84},
      {86, 80, 26, 23, 88, 25}, {49, 41, 8, 55, 65, 36}, {18, 33, 8, 42, 38, 77}, {75, 3, 82, 95, 102, 58}};
  ExactOptions always;
  always.mode = ExactMode::always;
  const FriedmanResult r = friedman_blocks(y, always);
  EXPECT_FALSE(r.ties);
  EXPECT_EQ(r.exact_method, "exact");
  EXPECT_TRUE(r.exact_note.empty());
  EXPECT_TRUE(near_rel(r.Q, 6.047619047619048, 1e-12));
  EXPECT_TRUE(near_rel(r.p_exact, 5984015105972443171753432509655680.0L / 19408409961765342806016000000000000.0L, 1e-12));
  // --exact auto (3e8 state updates) leaves it (9.4e8) and says why.
  const FriedmanResult automatic = friedman_blocks(y);
  EXPECT_EQ(automatic.exact_method, "none");
  EXPECT_NE(automatic.exact_note.find("state updates for n = 12, k = 6"), std::string::npos) << automatic.exact_note;
}

// Broke: at k = 8, n = 12 `always` spent 25 s and gave no p_exact with an
// empty exact_note. The work is bounded before any enumeration: the note
// says why at once, and p_exact is null.
TEST(Friedman, BeyondTheBudgetTheNoteSaysWhy) {
  std::vector<std::vector<double>> y;
  for (int i = 0; i < 12; ++i) {
    std::vector<double> row;
    for (int j = 0; j < 8; ++j) row.push_back((i * 5 + j * 3) % 8 + 0.5 * j);
    y.push_back(row);
  }
  ExactOptions always;
  always.mode = ExactMode::always;
  const FriedmanResult r = friedman_blocks(y, always);
  EXPECT_TRUE(std::isnan(r.p_exact));
  EXPECT_EQ(r.exact_method, "none");
  EXPECT_NE(r.exact_note.find("not enumerated: it needs more than 3e+09 state updates for n = 12, k = 8 (the limit)"),
            std::string::npos)
      << r.exact_note;
  EXPECT_NE(r.exact_note.find("monte-carlo=N"), std::string::npos) << r.exact_note;
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("p_exact not enumerated"), std::string::npos);
  EXPECT_GT(detail::friedman_exact_work(untied(8, 12)), 3e9);
}

TEST(Friedman, MonteCarloIsSeededAndAgreesWithExact) {
  ExactOptions mc;
  mc.mode = ExactMode::monte_carlo;
  mc.monte_carlo_samples = 40000;
  mc.seed = 7;
  const FriedmanResult a = friedman_blocks(kRoundingTimes, mc);
  const FriedmanResult b = friedman_blocks(kRoundingTimes, mc);
  EXPECT_EQ(a.exact_method, "monte-carlo");
  EXPECT_EQ(a.p_exact, b.p_exact) << "same seed, same resamples";
  mc.seed = 8;
  EXPECT_NE(friedman_blocks(kRoundingTimes, mc).p_exact, a.p_exact);
  const double exact = 0.00314983, se = std::sqrt(exact * (1 - exact) / 40000);
  EXPECT_NEAR(a.p_exact, exact, 4 * se);
}

TEST(Friedman, NeverSkipsTheExactP) {
  ExactOptions never;
  never.mode = ExactMode::never;
  const FriedmanResult r = friedman_blocks(kRoundingTimes, never);
  EXPECT_TRUE(std::isnan(r.p_exact));
  EXPECT_EQ(r.exact_method, "none");
}

TEST(FriedmanHardCases, EveryBlockTiedIsUndefined) {
  const FriedmanResult r = friedman_blocks({{1, 1, 1}, {2, 2, 2}, {5, 5, 5}});
  EXPECT_TRUE(std::isnan(r.Q));
  EXPECT_TRUE(std::isnan(r.p));
  EXPECT_TRUE(std::isnan(r.p_exact));
  EXPECT_TRUE(std::isnan(r.kendall_W));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("fully tied"), std::string::npos);
}

TEST(FriedmanHardCases, PerfectAgreement) {
  const FriedmanResult r = friedman_blocks({{1, 2, 3}, {1, 2, 3}, {4, 5, 6}, {0, 1, 9}, {2, 3, 4}});
  EXPECT_DOUBLE_EQ(r.Q, 10.0);  // n (k - 1)
  EXPECT_DOUBLE_EQ(r.kendall_W, 1.0);
  EXPECT_EQ(r.iman_davenport_F, INFINITY);
  EXPECT_EQ(r.p_iman_davenport, 0.0);
  // exact: only the 6 identical orderings reach S_max: P = 6 / 6^5 = 1/1296 (reference table k=3 n=5)
  EXPECT_TRUE(near_rel(r.p_exact, 1.0 / 1296, 1e-12));
}

TEST(FriedmanHardCases, OneBlockAndOneTreatment) {
  const FriedmanResult one_block = friedman_blocks({{3, 1, 2}});
  EXPECT_DOUBLE_EQ(one_block.Q, 2.0);
  EXPECT_TRUE(std::isnan(one_block.iman_davenport_F));
  const FriedmanResult one_treatment = friedman_blocks({{3}, {1}});
  EXPECT_TRUE(std::isnan(one_treatment.Q));
  EXPECT_FALSE(one_treatment.warnings.empty());
}

TEST(FriedmanHardCases, IncompleteBlocksAreDroppedAndNamed) {
  const LongData d = test::long_from_text(
      "id,cond,y\nb1,x,1\nb1,y,2\nb1,z,3\nb2,x,2\nb2,y,1\nb2,z,3\nb3,x,1\nb3,z,3\nb4,x,3\nb4,y,2\nb4,z,NA\n",
      {"y", "id", {"cond"}, {}});
  auto r = friedman(d);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->n, 2u);
  ASSERT_EQ(r->dropped_blocks.size(), 2u);
  EXPECT_EQ(r->dropped_blocks[0], "b3");
  EXPECT_EQ(r->dropped_blocks[1], "b4");
  EXPECT_DOUBLE_EQ(r->Q, friedman_blocks({{1, 2, 3}, {2, 1, 3}}).Q);
  EXPECT_NE(r->warnings[0].find("b3 (cond=y)"), std::string::npos) << r->warnings[0];
}

TEST(FriedmanHardCases, PFarBelowTheDoubleRange) {
  // 1000 blocks in perfect agreement, k = 3: Q = 2000, P(X2(2) >= 2000) = exp(-1000).
  std::vector<std::vector<double>> y(1000, {1.0, 2.0, 3.0});
  ExactOptions never;
  never.mode = ExactMode::never;
  const FriedmanResult r = friedman_blocks(y, never);
  EXPECT_DOUBLE_EQ(r.Q, 2000.0);
  EXPECT_EQ(r.p, 0.0);
  EXPECT_TRUE(near_rel(r.log10_p, -1000.0 / std::log(10.0), 1e-12));
}

}  // namespace
}  // namespace dtlab::stats
