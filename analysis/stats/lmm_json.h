// JSON of the mixed-model results (lmm.h, emmeans.h): the one definition of
// the fields `dtlab stats lmm --json` prints and report.json can store.
// Numbers are exact doubles (NaN null, infinities "Infinity"/"-Infinity",
// json.h's json_number); names follow R's output (lme4 summary, lmerTest
// anova, VarCorr, emmeans). No rounding here.
// Example: std::cout << lmm_fit_json(*fit).dump(2);  emm_table_json(*marginal_means(*fit, {"A"}))
#pragma once
#include <nlohmann/json.hpp>

#include "analysis/stats/emmeans.h"
#include "analysis/stats/json.h"
#include "analysis/stats/lmm.h"

namespace dtlab::stats {

inline const char* family_name(Family f) { return f == Family::binomial ? "binomial" : "gaussian"; }

template <class J = nlohmann::ordered_json>
J lmm_fit_json(const LmmFit& f) {
  auto n = [](double v) { return json_number<J>(v); };
  const bool z = f.family == Family::binomial;
  J coefficients = J::array();
  for (const auto& c : f.coefficients)
    coefficients.push_back(J{{"name", c.name}, {"estimate", n(c.estimate)}, {"se", n(c.se)}, {"df", n(c.df)},
                             {z ? "z" : "t", n(c.statistic)}, {"p", n(c.p)}, {"log10_p", n(c.log10_p)}});
  J anova = J::array();
  for (const auto& a : f.anova)
    anova.push_back(J{{"term", a.term}, {"sum_sq", n(a.sum_sq)}, {"mean_sq", n(a.mean_sq)}, {"num_df", n(a.num_df)},
                      {"den_df", n(a.den_df)}, {"F", n(a.F)}, {"p", n(a.p)}, {"log10_p", n(a.log10_p)}});
  J lrt = J::array();
  for (const auto& l : f.lrt)
    lrt.push_back(J{{"term", l.term}, {"df", n(l.df)}, {"chisq", n(l.chisq)}, {"p", n(l.p)}, {"log10_p", n(l.log10_p)},
                    {"deviance_full", n(l.deviance_full)}, {"deviance_reduced", n(l.deviance_reduced)},
                    {"warnings", l.warnings}});
  J variances = J::array();
  for (const auto& v : f.variances)
    variances.push_back(J{{"group", v.group}, {"name", v.name}, {"variance", n(v.variance)}, {"sd", n(v.sd)}});
  J correlations = J::array();
  for (const auto& c : f.correlations)
    correlations.push_back(J{{"group", c.group}, {"a", c.a}, {"b", c.b}, {"r", n(c.r)}});
  J random = J::array();
  for (const auto& r : f.random) random.push_back(J{{"grouping", r.grouping}, {"columns", r.columns}, {"correlated", r.correlated}});
  J groups = J::array();
  for (const auto& [name, levels] : f.groups) groups.push_back(J{{"name", name}, {"levels", levels}});
  J theta = J::array();
  for (double t : f.theta) theta.push_back(n(t));
  return J{{"family", family_name(f.family)},
           {"method", f.family == Family::binomial ? "Laplace" : f.reml ? "REML" : "ML"},
           {"transform", f.transform == Transform::log ? "log" : "none"},
           {"formula", f.formula},
           {"ddf", f.family == Family::binomial ? "none (Wald z)" : f.kenward_roger ? "Kenward-Roger" : "Satterthwaite"},
           {"n", f.n},
           {"groups", groups},
           {"random", random},
           {"fallback", f.fallback},
           {"coefficients", coefficients},
           {"anova", anova},
           {"lrt", lrt},
           {"variances", variances},
           {"correlations", correlations},
           {"sigma", n(f.sigma)},
           {"theta", theta},
           {"reml_criterion", n(f.reml_criterion)},
           {"deviance", n(f.deviance)},
           {"loglik", n(f.loglik)},
           {"df", f.df},
           {"aic", n(f.aic)},
           {"bic", n(f.bic)},
           {"singular", f.singular},
           {"messages", f.messages},
           {"warnings", f.warnings},
           {"r_code", f.r_code}};
}

template <class J = nlohmann::ordered_json>
J emm_table_json(const EmmTable& t) {
  auto n = [](double v) { return json_number<J>(v); };
  const char* scale = t.scale == EmmScale::log ? "log" : t.scale == EmmScale::logit ? "logit" : "identity";
  J means = J::array();
  for (const auto& m : t.means) {
    J lv = J::object();
    for (size_t i = 0; i < t.factors.size(); ++i) lv[t.factors[i]] = m.levels[i];
    means.push_back(J{{"cell", lv}, {"emmean", n(m.estimate)}, {"se", n(m.se)}, {"df", n(m.df)},
                      {"ci_low", n(m.ci_low)}, {"ci_high", n(m.ci_high)}, {"response", n(m.response)},
                      {"response_ci_low", n(m.response_ci_low)}, {"response_ci_high", n(m.response_ci_high)}});
  }
  J contrasts = J::array();
  for (const auto& c : t.contrasts)
    contrasts.push_back(J{{"contrast", c.a + " - " + c.b}, {"a", c.a}, {"b", c.b}, {"estimate", n(c.estimate)},
                          {"se", n(c.se)}, {"df", n(c.df)}, {"statistic", n(c.statistic)}, {"p", n(c.p)},
                          {"log10_p", n(c.log10_p)}, {"p_holm", n(c.p_holm)}, {"ci_low", n(c.ci_low)},
                          {"ci_high", n(c.ci_high)}, {"ratio", n(c.ratio)}, {"ratio_ci_low", n(c.ratio_ci_low)},
                          {"ratio_ci_high", n(c.ratio_ci_high)}});
  return J{{"factors", t.factors}, {"scale", scale}, {"means", means}, {"contrasts", contrasts}};
}

}  // namespace dtlab::stats
