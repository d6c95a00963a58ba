// Tests on participant x cell tables; see inference.h. The statistics themselves
// are analysis/stats' (validated there against R and NIST); this file only
// chooses the data each test sees and collects what the tables show.
#include "analysis/report/detail/inference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/report/detail/format.h"
#include "analysis/stats/apa.h"

namespace dtlab::report::detail {
namespace {


// What every test report holds: names, the participants kept, cell and marginal descriptives.
// False, with not_tested set, when nothing can be tested.
bool begin_report(TestReport& r, const CellMatrix& m, std::string test, std::string measure, std::string unit,
                  std::string scope) {
  r.test = std::move(test);
  r.measure = std::move(measure);
  r.unit = std::move(unit);
  r.scope = std::move(scope);
  r.m = &m;
  r.kept = m.complete();
  r.excluded = m.missing_notes();
  for (size_t c = 0; c < m.cells(); ++c) {
    std::vector<double> v;
    for (size_t s : r.kept) v.push_back(m.value[s][c]);
    r.cells.push_back(stats::describe(v));
  }
  for (size_t k = 0; k < m.factors.size(); ++k) {
    std::vector<stats::Descriptives> per_level;
    int levels = 0;
    for (size_t c = 0; c < m.cells(); ++c) levels = std::max(levels, m.level(c, k) + 1);
    for (int l = 0; l < levels; ++l) {
      const auto all = marginal(m, k, l);
      std::vector<double> v;
      for (size_t s : r.kept) v.push_back(all[s]);
      per_level.push_back(stats::describe(v));
    }
    r.marginals.push_back(std::move(per_level));
  }
  if (m.factors.empty()) {
    r.not_tested = "no factor varies";
    return false;
  }
  if (r.kept.empty()) {
    r.not_tested = "no participant has a value in every cell";
    return false;
  }
  return true;
}

// The paired difference of a two-level primary factor (marginal means).
void paired_effect(TestReport& r, const CellMatrix& m, const Design& d) {
  for (size_t k = 0; k < m.factors.size(); ++k) {
    if (m.factors[k] != d.primary || d.factor(d.primary).levels.size() != 2 || r.kept.size() < 2) continue;
    const auto a = marginal(m, k, 0), b = marginal(m, k, 1);
    std::vector<double> x, y;
    for (size_t s : r.kept) {
      x.push_back(b[s]);
      y.push_back(a[s]);
    }
    PairedEffect e;
    e.factor = d.primary;
    e.t = stats::paired_t(x, y);
    e.dz = e.t.sd > 0 ? e.t.mean_difference / e.t.sd : kNaN;
    r.paired = e;
  }
}

}  // namespace

double reported_p(const stats::Effect& e) {
  return stats::applied_correction(e, stats::Correction::greenhouse_geisser) == stats::Correction::none ? e.p : e.p_gg;
}

namespace {

// Simple effects and within-subject CIs of every two-way within interaction with p < kFollowUpAlpha.
void follow_up(TestReport& r, const stats::LongData& data) {
  for (const auto& e : r.anova->effects) {
    const auto colon = e.name.find(':');
    if (colon == std::string::npos || e.name.find(':', colon + 1) != std::string::npos) continue;
    if (!(reported_p(e) < kFollowUpAlpha)) continue;
    InteractionFollowUp f{e.name, e.name.substr(0, colon), e.name.substr(colon + 1), {}, {}};
    stats::LongData sub = data;
    sub.within.clear();
    for (const auto& w : data.within)
      if (w.name == f.a || w.name == f.b) sub.within.push_back(w);
    if (sub.within.size() != 2 || !data.between.empty()) continue;  // a between factor: not followed up
    sub.aggregate = stats::Aggregate::mean;  // each participant's mean over the other within factors
    auto simple = stats::simple_effects(sub, f.a, f.b);
    auto ci = stats::within_subject_intervals(sub, 0.95);
    if (!simple || !ci) {
      r.warnings.push_back("follow-up of " + e.name + " not computed: " +
                           (simple ? ci.error().message : simple.error().message));
      continue;
    }
    f.simple = std::move(*simple);
    f.intervals = std::move(*ci);
    r.followups.push_back(std::move(f));
  }
}

// Shapiro-Wilk of the residuals of the within-subject model.
void normality(TestReport& r, const stats::LongData& data) {
  auto res = stats::anova_residuals(data);
  if (!res) return;
  for (const auto& e : res->residuals) r.residuals.push_back(e.value);
  r.normality = stats::shapiro_wilk(r.residuals);
}

}  // namespace

const stats::Effect* TestReport::effect(const std::string& name) const {
  if (!anova) return nullptr;
  for (const auto& e : anova->effects)
    if (e.name == name) return &e;
  return nullptr;
}

const std::vector<stats::Descriptives>* TestReport::marginal_of(int f) const {
  for (size_t k = 0; k < m->factors.size(); ++k)
    if (m->factors[k] == f) return &marginals[k];
  return nullptr;
}

Result<stats::RmAnovaResult> rm_anova_of(const CellMatrix& m, const Design& d, const std::vector<size_t>& kept) {
  return stats::rm_anova(long_data(m, d, kept, "y"));
}

TestReport run_rm_anova(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope) {
  TestReport r;
  if (!begin_report(r, m, "rm-anova", std::move(measure), std::move(unit), std::move(scope))) return r;
  const auto data = long_data(m, d, r.kept, "y");
  auto res = stats::rm_anova(data);  // = rm_anova_of(m, d, r.kept); the data serve the post-hoc tests too
  if (!res) {
    r.not_tested = res.error().message;
    return r;
  }
  r.warnings = res->warnings;
  r.anova = std::move(*res);
  if (r.kept.size() < 2) r.not_tested = "one participant: no error variance, F is undefined";
  if (r.kept.size() >= 2) {
    follow_up(r, data);
    normality(r, data);
  }
  for (size_t k = 0; k < m.factors.size(); ++k) {
    const auto& f = d.factor(m.factors[k]);
    if (f.levels.size() < 3 || r.kept.size() < 2) continue;
    auto ph = stats::pairwise_within(data, f.name, stats::PairwiseTest::paired_t);
    if (ph) r.posthoc[f.name] = std::move(*ph);
  }
  paired_effect(r, m, d);
  return r;
}

TestReport run_friedman(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                        std::string scope, std::uint64_t seed) {
  TestReport r;
  if (!begin_report(r, m, "friedman", std::move(measure), std::move(unit), std::move(scope))) return r;
  const auto data = long_data(m, d, r.kept, "y");
  stats::ExactOptions exact;
  exact.seed = seed;
  auto res = stats::friedman(data, exact);
  if (!res) {
    r.not_tested = res.error().message;
    return r;
  }
  r.warnings = res->warnings;
  r.friedman = std::move(*res);
  for (size_t k = 0; k < m.factors.size(); ++k) {
    const auto& f = d.factor(m.factors[k]);
    if (f.levels.size() < 3 || r.kept.size() < 2) continue;
    stats::WilcoxonOptions wo;
    wo.exact.seed = seed;
    auto ph = stats::pairwise_within(data, f.name, stats::PairwiseTest::wilcoxon, wo);
    if (ph) r.posthoc[f.name] = std::move(*ph);
  }
  paired_effect(r, m, d);
  return r;
}

TestReport run_rank_test(const CellMatrix& m, const Design& d, std::string measure, std::string unit,
                         std::string scope, std::uint64_t seed) {
  if (m.factors.size() != 1 || m.cells() != 2)
    return run_friedman(m, d, std::move(measure), std::move(unit), std::move(scope), seed);
  TestReport r;
  if (!begin_report(r, m, "wilcoxon", std::move(measure), std::move(unit), std::move(scope))) return r;
  std::vector<double> x, y;
  for (size_t s : r.kept) {
    x.push_back(m.value[s][0]);
    y.push_back(m.value[s][1]);
  }
  stats::WilcoxonOptions wo;
  wo.exact.seed = seed;
  r.wilcoxon = stats::wilcoxon_signed_rank(x, y, wo);
  r.warnings = r.wilcoxon->warnings;
  return r;
}

std::string effect_sentence(const stats::Effect& e) {
  return stats::apa_effect(e, stats::Correction::greenhouse_geisser);
}

std::string friedman_sentence(const stats::FriedmanResult& f) {
  std::string s = "χ²(" + stats::apa_df(f.df) + ") = " + stats::apa_number(f.Q) + ", " + stats::apa_p(f.p);
  if (std::isfinite(f.p_exact)) s += " (exact " + stats::apa_p(f.p_exact) + ")";
  return s + ", Kendall's W = " + stats::apa_bounded(f.kendall_W) + ", n = " + std::to_string(f.n);
}

double rank_biserial(const stats::WilcoxonResult& w) {
  const double n = static_cast<double>(w.n);
  return w.n == 0 ? kNaN : 4 * w.V / (n * (n + 1)) - 1;
}

std::string wilcoxon_sentence(const stats::WilcoxonResult& w) {
  std::string s = stats::apa_wilcoxon(w);
  if (w.method != "exact" && std::isfinite(w.p_exact)) s += " (exact " + stats::apa_p(w.p_exact) + ")";
  return s + ", r_rb = " + stats::apa_bounded(rank_biserial(w)) + ", n = " + std::to_string(w.n);
}

}  // namespace dtlab::report::detail
