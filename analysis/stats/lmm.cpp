// Mixed models on trial-level data; see lmm.h. This file holds the public
// entry points and the fallback of --random max; the fits are in detail/.
#include "analysis/stats/lmm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/stats/detail/glmm.h"
#include "analysis/stats/detail/lmm_fit.h"
#include "analysis/stats/detail/lmm_model.h"
#include "analysis/stats/detail/satterthwaite.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {
namespace {

using detail::FormulaTerm;
using detail::GaussianFit;
using detail::PreparedModel;

// Why a fit was not kept: lme4's singular message or its warnings.
template <class Fit>
std::string describe(const Fit& f) {
  if (f.conv.singular) return "singular fit (lme4: " + f.conv.messages.front() + ")";
  std::string s;
  for (const auto* list : {&f.opt.warnings, &f.conv.warnings, &f.warnings})
    for (const auto& w : *list) s += (s.empty() ? "" : "; ") + w;
  return "did not converge (" + s + ")";
}

// The slope column (not an intercept) with the smallest variance among the || terms.
template <class Fit>
bool drop_smallest_slope(const PreparedModel& m, const Fit& f, std::vector<FormulaTerm>& terms, std::string& what) {
  const auto variances = detail::column_variances(f);
  const auto& lme4_terms = f.lme4_terms();
  double best = std::numeric_limits<double>::infinity();
  int best_group = -1, best_column = -1;
  for (size_t t = 0; t < lme4_terms.size(); ++t)
    for (size_t j = 0; j < lme4_terms[t].columns.size(); ++j)
      if (lme4_terms[t].columns[j] != 0 && variances[t][j] < best) {
        best = variances[t][j];
        best_group = lme4_terms[t].grouping;
        best_column = lme4_terms[t].columns[j];
      }
  if (best_group < 0) return false;
  for (auto& t : terms)
    if (t.grouping == best_group) t.columns.erase(std::remove(t.columns.begin(), t.columns.end(), best_column), t.columns.end());
  char b[64];
  std::snprintf(b, sizeof b, "%.4g", best);
  what = "the by-" + m.groupings[static_cast<size_t>(best_group)].name + " slope " +
         m.design.column_names[static_cast<size_t>(best_column)] + " (variance " + b + ")";
  return true;
}

bool has_slopes(const std::vector<FormulaTerm>& terms) {
  for (const auto& t : terms)
    if (t.columns.size() > 1) return true;
  return false;
}

// --random max: maximal, then without correlations, then dropping the
// smallest slope variance, until a fit is regular (or only intercepts remain).
template <class Fit, class FitFn>
Fit fit_with_fallback(const PreparedModel& m, std::vector<FormulaTerm> terms, FitFn fit, std::vector<std::string>& steps) {
  Fit f = fit(terms);
  if (f.regular() || !has_slopes(terms)) return f;
  steps.push_back(detail::lme4_formula(m, terms) + ": " + describe(f) + "; refitted without correlations");
  for (auto& t : terms) t.correlated = false;
  f = fit(terms);
  while (!f.regular() && has_slopes(terms)) {
    std::string dropped;
    const std::string formula = detail::lme4_formula(m, terms);
    if (!drop_smallest_slope(m, f, terms, dropped)) break;
    steps.push_back(formula + ": " + describe(f) + "; dropped " + dropped);
    f = fit(terms);
  }
  steps.push_back(detail::lme4_formula(m, terms) + ": " +
                  (f.regular() ? std::string("kept") : "kept, " + describe(f) + ", with no slope left to drop"));
  return f;
}

// afex's method = "LRT" for an LMM: ML fits of the full model and of X without each term.
void add_gaussian_lrt(LmmFit& fit, const PreparedModel& m, const std::vector<FormulaTerm>& terms) {
  const double full = detail::fit_gaussian(m, m.design.X, terms, false).opt.fval;
  for (const auto& term : m.design.terms) {
    const GaussianFit reduced = detail::fit_gaussian(m, detail::drop_term(m.design, term), terms, false);
    LmmLrtRow row{term.name, static_cast<double>(term.columns.size()), 0, 0, 0, full, reduced.opt.fval, {}};
    row.chisq = std::max(0.0, reduced.opt.fval - full);
    const Tail tail = chi_squared_upper(row.chisq, row.df);
    row.p = tail.p;
    row.log10_p = tail.log10_p;
    row.warnings = reduced.conv.messages;
    row.warnings.insert(row.warnings.end(), reduced.conv.warnings.begin(), reduced.conv.warnings.end());
    fit.lrt.push_back(row);
  }
}

}  // namespace

Result<LmmData> lmm_data_from_csv(const CsvTable& table, const ColumnRoles& roles, const std::string& item) {
  for (const auto& name : roles.within)
    if (name == item) return Error{table.file, 1, 0, item, "column given for two roles (--item and --within)"};
  for (const auto& name : roles.between)
    if (name == item) return Error{table.file, 1, 0, item, "column given for two roles (--item and --between)"};
  if (!item.empty() && (item == roles.dv || item == roles.subject))
    return Error{table.file, 1, 0, item, "column given for two roles"};
  auto long_data = long_data_from_csv(table, roles);
  if (!long_data) return long_data.error();
  LmmData d;
  d.data = std::move(long_data).value();
  d.subject_name = roles.subject;
  if (item.empty()) return d;
  const int c = table.column(item);
  if (c < 0) return Error{table.file, 1, 0, name_for_message(item), "no such column for the item (--item)"};
  d.item_name = item;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& cell = table.rows[r][static_cast<size_t>(c)];
    if (is_missing_token(cell))
      return Error{table.file, table.line[r], c + 1, name_for_message(item), "empty or NA item: every row needs one"};
    d.item.push_back(cell);
  }
  return d;
}

Result<LmmFit> fit_lmm(const LmmData& data, const LmmOptions& o) {
  auto prepared = detail::prepare_model(data, o);
  if (!prepared) return prepared.error();
  const PreparedModel& m = *prepared;
  std::vector<std::string> steps;
  const std::vector<FormulaTerm> terms = detail::random_structure(m, o.random, steps);
  const bool max = o.random == RandomEffects::maximal;
  LmmFit fit;
  if (o.family == Family::binomial) {
    auto one = [&](const std::vector<FormulaTerm>& t) { return detail::fit_binomial(m, m.design.X, t); };
    detail::BinomialFit f = max ? fit_with_fallback<detail::BinomialFit>(m, terms, one, steps) : one(terms);
    fit = detail::report_binomial(m, f, o);
  } else {
    auto one = [&](const std::vector<FormulaTerm>& t) { return detail::fit_gaussian(m, m.design.X, t, o.reml); };
    GaussianFit f = max ? fit_with_fallback<GaussianFit>(m, terms, one, steps) : one(terms);
    fit = detail::report_gaussian(m, f, o);
    if (o.lrt) add_gaussian_lrt(fit, m, f.formula_terms);
  }
  fit.dv_name = data.data.dv_name;
  fit.fallback = steps;
  if (m.missing > 0)
    fit.warnings.push_back(std::to_string(m.missing) + (m.missing == 1 ? " row" : " rows") +
                           " with a missing " + data.data.dv_name + " left out");
  return fit;
}

double satterthwaite_df(const LmmFit& fit, const Eigen::RowVectorXd& L) {
  if (fit.jacobian.empty()) return std::numeric_limits<double>::infinity();
  return detail::satterthwaite_t_df(fit.vcov_varpar, fit.jacobian, fit.vcov_unadjusted, L);
}

}  // namespace dtlab::stats
