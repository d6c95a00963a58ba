// The tests the report runs on a CellMatrix, with everything a results table
// needs: per cell and per level descriptives over the participants the test
// keeps, the test itself (analysis/stats), Holm post-hoc comparisons for
// factors with more than two levels, and for a two-level primary factor the
// paired difference with its 95% CI and Cohen's d_z; for ANOVAs also the
// follow-up of each significant two-way interaction and Shapiro-Wilk of the
// residuals; rank tests (Wilcoxon, Friedman). Missing data: listwise
// deletion, done here so the report can name each excluded participant and
// cell. A test that cannot run (no complete participant) is reported with
// its reason, never as an error of the whole report.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/report/detail/cells.h"
#include "analysis/report/detail/report_design.h"
#include "analysis/stats/stats.h"

namespace dtlab::report::detail {

struct PairedEffect {
  int factor = -1;                  // design factor index
  int a = 0, b = 1;                 // levels: difference is b - a (e.g. on - off)
  stats::PairedTResult t;           // mean_difference, 95% CI, t, df, p
  double dz = 0;                    // Cohen's d_z = mean difference / SD of the differences
};

// The follow-up of a two-way interaction of within factors with p < .05 (GG-corrected
// where ε < 1): simple effects (stats::simple_effects) and the Cousineau-Morey 95%
// within-subject CIs of the a x b cell means (each participant's values first averaged
// over the other within factors).
struct InteractionFollowUp {
  std::string effect;                          // "transparency:scenario"
  std::string a, b;                            // its two factors, ANOVA order
  stats::SimpleEffects simple;                 // a at each level of b, then b at each level of a
  std::vector<stats::CellInterval> intervals;  // a x b cells, b varying fastest
};

struct TestReport {
  std::string measure, unit, scope;          // e.g. "completion time", "s", "T1"
  std::string test;                          // "rm-anova" or "friedman"
  const CellMatrix* m = nullptr;
  std::vector<size_t> kept;                  // complete subjects (indices into m->subjects)
  std::vector<std::string> excluded;         // missing_notes() of the others
  std::vector<stats::Descriptives> cells;    // per cell, over kept subjects
  std::vector<std::vector<stats::Descriptives>> marginals;  // [factor entry][level], over kept subjects
  std::optional<stats::RmAnovaResult> anova;
  std::optional<stats::FriedmanResult> friedman;
  std::optional<stats::WilcoxonResult> wilcoxon;  // test "wilcoxon": first level (x) vs second (y)
  std::map<std::string, std::vector<stats::Comparison>> posthoc;  // factor name -> Holm-corrected pairs
  std::optional<PairedEffect> paired;       // two-level primary factor among m->factors
  std::vector<InteractionFollowUp> followups;  // significant two-way within interactions (rm-anova)
  std::optional<stats::ShapiroWilkResult> normality;  // Shapiro-Wilk of the ANOVA residuals (rm-anova)
  std::vector<double> residuals;            // those residuals (subject-major), for a Q-Q plot
  std::string not_tested;                   // why no test ran ("" when one did)
  std::vector<std::string> warnings;        // from the statistics library

  // The effect row of `name` ("transparency", "transparency:scenario"), or nullptr.
  const stats::Effect* effect(const std::string& name) const;
  // The marginal descriptives of design factor f (nullptr if f is not among m->factors).
  const std::vector<stats::Descriptives>* marginal_of(int f) const;
};

TestReport run_rm_anova(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope);
// The repeated-measures ANOVA run_rm_anova runs, alone: over the `kept` subjects of m (power planning reruns it).
Result<stats::RmAnovaResult> rm_anova_of(const CellMatrix& m, const Design& d, const std::vector<size_t>& kept);
TestReport run_friedman(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope, std::uint64_t seed);
// The rank test of a one-factor matrix (marginal_matrix): two levels, the Wilcoxon signed-rank
// test of the first level against the second (R's wilcox.test(x, y, paired = TRUE) defaults);
// more levels, Friedman's test.
TestReport run_rank_test(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                         std::string scope, std::uint64_t seed);

// The p the report prints and judges an effect by: Greenhouse-Geisser corrected where ε < 1.
double reported_p(const stats::Effect& e);

// The significance level at which an interaction is followed up.
inline constexpr double kFollowUpAlpha = 0.05;

// The APA sentence of an effect, Greenhouse-Geisser corrected where ε < 1 (stats::apa_effect):
// "F(1, 15) = 20.09, p < .001, ηp² = .57, 90% CI [.25, .74]"; for Friedman
// "χ²(1) = 6.25, p = .012 (exact p = .021), Kendall's W = .39, n = 16"; for Wilcoxon
// "V = 120, p < .001, r_rb = .76, n = 16" (matched-pairs rank-biserial correlation).
std::string effect_sentence(const stats::Effect& e);
std::string friedman_sentence(const stats::FriedmanResult& f);
std::string wilcoxon_sentence(const stats::WilcoxonResult& w);
// Matched-pairs rank-biserial correlation (Kerby 2014): (T+ − T−) / (T+ + T−) = 4 V / (n (n + 1)) − 1.
double rank_biserial(const stats::WilcoxonResult& w);

}  // namespace dtlab::report::detail
