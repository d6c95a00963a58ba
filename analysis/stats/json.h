// JSON of the statistics results: the one definition of the fields that
// `dtlab stats --json` prints and report.json stores, so the two can never
// diverge. Numbers are exact doubles (nlohmann-json prints the shortest text
// that reads back to the same double); NaN is null, infinities are the
// strings "Infinity" / "-Infinity". No rounding happens here: rounding is for
// text only (apa.h). Templates over the JSON type so callers may use
// nlohmann::json or nlohmann::ordered_json (the default keeps field order).
#pragma once
#include <nlohmann/json.hpp>

#include <cmath>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/descriptives.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/posthoc.h"

namespace dtlab::stats {

// A double as JSON: null for NaN, "Infinity" / "-Infinity" for infinities.
template <class J = nlohmann::ordered_json>
J json_number(double v) {
  if (std::isnan(v)) return J(nullptr);
  if (std::isinf(v)) return J(v > 0 ? "Infinity" : "-Infinity");
  return J(v);
}

// One ANOVA row: every field of Effect.
template <class J = nlohmann::ordered_json>
J effect_json(const Effect& e) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"effect", e.name},
           {"df1", n(e.df1)},
           {"df2", n(e.df2)},
           {"ss", n(e.ss)},
           {"ss_error", n(e.ss_error)},
           {"mse", n(e.mse)},
           {"F", n(e.F)},
           {"p", n(e.p)},
           {"log10_p", n(e.log10_p)},
           {"eta_p2", n(e.eta_p2)},
           {"eta_p2_ci90_low", n(e.eta_p2_ci_low)},
           {"eta_p2_ci90_high", n(e.eta_p2_ci_high)},
           {"eta_g2", n(e.eta_g2)},
           {"mauchly_W", n(e.mauchly_W)},
           {"mauchly_p", n(e.mauchly_p)},
           {"gg_epsilon", n(e.gg_epsilon)},
           {"hf_epsilon", n(e.hf_epsilon)},
           {"df1_gg", n(e.df1_gg)},
           {"df2_gg", n(e.df2_gg)},
           {"mse_gg", n(e.mse_gg)},
           {"p_gg", n(e.p_gg)},
           {"log10_p_gg", n(e.log10_p_gg)},
           {"df1_hf", n(e.df1_hf)},
           {"df2_hf", n(e.df2_hf)},
           {"mse_hf", n(e.mse_hf)},
           {"p_hf", n(e.p_hf)},
           {"log10_p_hf", n(e.log10_p_hf)}};
}

template <class J = nlohmann::ordered_json>
J descriptives_json(const Descriptives& d) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"n", d.n},           {"mean", n(d.mean)}, {"sd", n(d.sd)},   {"se", n(d.se)},   {"ci_low", n(d.ci_low)},
           {"ci_high", n(d.ci_high)}, {"median", n(d.median)}, {"q1", n(d.q1)}, {"q3", n(d.q3)}, {"iqr", n(d.iqr)},
           {"min", n(d.min)},    {"max", n(d.max)}};
}

// A post-hoc / simple-effect comparison row.
template <class J = nlohmann::ordered_json>
J comparison_json(const Comparison& c) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"a", c.a},
           {"b", c.b},
           {"test", c.test},
           {"n", c.n},
           {"estimate", n(c.estimate)},
           {"se", n(c.se)},
           {"ci_low", n(c.ci_low)},
           {"ci_high", n(c.ci_high)},
           {"statistic", n(c.statistic)},
           {"df", n(c.df)},
           {"p", n(c.p)},
           {"p_holm", n(c.p_holm)},
           {"dz", n(c.dz)}};
}

template <class J = nlohmann::ordered_json>
J comparisons_json(const std::vector<Comparison>& cs) {
  J a = J::array();
  for (const auto& c : cs) a.push_back(comparison_json<J>(c));
  return a;
}

// A joint (Wald) F test of several contrasts, as emmeans' joint_tests: the
// effect, df1, df2, F, p and log10_p of an Effect row (its other fields do not apply).
template <class J = nlohmann::ordered_json>
J joint_test_json(const Effect& e) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"effect", e.name}, {"df1", n(e.df1)}, {"df2", n(e.df2)}, {"F", n(e.F)}, {"p", n(e.p)}, {"log10_p", n(e.log10_p)}};
}

template <class J = nlohmann::ordered_json>
J friedman_json(const FriedmanResult& f) {
  auto n = [](double v) { return json_number<J>(v); };
  J ranks = J::array();
  for (double r : f.mean_ranks) ranks.push_back(n(r));
  J j{{"n", f.n},
      {"k", f.k},
      {"treatments", f.treatments},
      {"mean_ranks", ranks},
      {"Q", n(f.Q)},
      {"df", n(f.df)},
      {"p", n(f.p)},
      {"log10_p", n(f.log10_p)},
      {"p_exact", n(f.p_exact)},
      {"exact_method", f.exact_method},
      {"exact_note", f.exact_note.empty() ? J(nullptr) : J(f.exact_note)},
      {"kendall_W", n(f.kendall_W)},
      {"iman_davenport_F", n(f.iman_davenport_F)},
      {"iman_davenport_df1", n(f.id_df1)},
      {"iman_davenport_df2", n(f.id_df2)},
      {"p_iman_davenport", n(f.p_iman_davenport)},
      {"log10_p_iman_davenport", n(f.log10_p_iman_davenport)},
      {"ties", f.ties}};
  if (f.exact_method == "monte-carlo") {
    j["monte_carlo_samples"] = f.monte_carlo_samples;
    j["seed"] = f.seed;
  }
  return j;
}

template <class J = nlohmann::ordered_json>
J wilcoxon_json(const WilcoxonResult& w) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"V", n(w.V)},
           {"p", n(w.p)},
           {"log10_p", n(w.log10_p)},
           {"method", w.method},
           {"p_exact", n(w.p_exact)},
           {"exact_method", w.exact_method},
           {"exact_note", w.exact_note.empty() ? J(nullptr) : J(w.exact_note)},
           {"z", n(w.z)},
           {"p_normal", n(w.p_normal)},
           {"n", w.n},
           {"pairs", w.pairs},
           {"zeros", w.zeros},
           {"ties", w.ties}};
}

template <class J = nlohmann::ordered_json>
J sign_test_json(const SignTestResult& s) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"n", s.n}, {"positive", s.positive}, {"negative", s.negative}, {"p", n(s.p)}, {"log10_p", n(s.log10_p)}};
}

template <class J = nlohmann::ordered_json>
J paired_t_json(const PairedTResult& t) {
  auto n = [](double v) { return json_number<J>(v); };
  return J{{"n", t.n},
           {"mean_difference", n(t.mean_difference)},
           {"sd", n(t.sd)},
           {"se", n(t.se)},
           {"ci_low", n(t.ci_low)},
           {"ci_high", n(t.ci_high)},
           {"t", n(t.t)},
           {"df", n(t.df)},
           {"p", n(t.p)},
           {"log10_p", n(t.log10_p)},
           {"dz", n(t.dz)}};
}

}  // namespace dtlab::stats
