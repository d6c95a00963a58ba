// Data checks, random-effects structures and formula text; see lmm_model.h.
#include "analysis/stats/detail/lmm_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

namespace dtlab::stats::detail {
namespace {

Error row_error(const LongData& d, size_t row, const std::string& field, const std::string& message) {
  Error e{d.source, row < d.line.size() ? d.line[row] : 0, 0, field, message};
  return e;
}

Grouping make_grouping(const std::string& name, const std::vector<std::string>& labels) {
  const CodedFactor f = code_factor(name, labels, true);
  return {f.name, f.levels, f.index};
}

// A between factor must keep one level per subject.
Status check_between(const LongData& d, const std::vector<size_t>& rows) {
  for (const auto& f : d.between) {
    std::unordered_map<std::string, size_t> first;
    for (size_t r : rows) {
      auto [it, fresh] = first.try_emplace(d.subject[r], r);
      if (!fresh && f.level[it->second] != f.level[r])
        return row_error(d, r, f.name,
                         "between-subject factor changes within subject " + name_for_message(d.subject[r]) + " (" +
                             quote_text(f.level[it->second]) + " on " + d.where(it->second) + ", " +
                             quote_text(f.level[r]) + " here); name it with --within");
    }
  }
  return {};
}

// Every cell of the full factorial needs a row (else lme4 drops columns of X).
Status check_cells(const FixedDesign& design, const std::string& source) {
  if (design.factors.empty()) return {};
  std::set<std::vector<int>> seen;
  const size_t n = design.factors.front().index.size();
  for (size_t r = 0; r < n; ++r) {
    std::vector<int> cell;
    for (const auto& f : design.factors) cell.push_back(f.index[r]);
    seen.insert(cell);
  }
  std::vector<int> cell(design.factors.size(), 0);
  while (true) {
    if (!seen.count(cell)) {
      std::string name;
      for (size_t f = 0; f < cell.size(); ++f)
        name += (f ? ", " : "") + design.factors[f].name + "=" + design.factors[f].levels[static_cast<size_t>(cell[f])];
      return Error{source, 0, 0, "", "no row with a dv value in the cell " + name +
                                         ": a mixed model on the full factorial needs every cell"};
    }
    size_t f = 0;
    for (; f < cell.size(); ++f) {
      if (++cell[f] < static_cast<int>(design.factors[f].levels.size())) break;
      cell[f] = 0;
    }
    if (f == cell.size()) break;
  }
  return {};
}

std::vector<bool> varies_within(const Grouping& g, const std::vector<CodedFactor>& factors) {
  std::vector<bool> v;
  for (const auto& f : factors) {
    std::vector<int> first(g.levels.size(), -1);
    bool changes = false;
    for (size_t r = 0; r < f.index.size() && !changes; ++r) {
      int& l = first[static_cast<size_t>(g.index[r])];
      if (l < 0) l = f.index[r];
      changes = l != f.index[r];
    }
    v.push_back(changes);
  }
  return v;
}

}  // namespace

std::string r_name(const std::string& name) {
  bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '.');
  if (ok && name[0] == '.' && name.size() > 1 && std::isdigit(static_cast<unsigned char>(name[1]))) ok = false;
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_');
  static const std::set<std::string> reserved{"if", "else", "repeat", "while", "function", "for", "next", "break",
                                              "TRUE", "FALSE", "NULL", "Inf", "NaN", "NA", "in"};
  if (ok && !reserved.count(name)) return name;
  std::string s = "`";
  for (char c : name) s += c == '`' ? std::string("\\`") : std::string(1, c);
  return s + "`";
}

std::string re_column_name(const PreparedModel& m, int column) {
  std::string s = "re_";
  for (char c : m.design.column_names[static_cast<size_t>(column)])
    s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

Result<PreparedModel> prepare_model(const LmmData& data, const LmmOptions& o) {
  const LongData& d = data.data;
  PreparedModel m;
  m.rows_read = d.rows();
  if (d.subject.size() != d.rows()) return Error{d.source, 0, 0, "", "a mixed model needs a subject column (--subject)"};
  if (!data.item_name.empty() && data.item.size() != d.rows())
    return Error{d.source, 0, 0, data.item_name, "the item column has the wrong number of rows"};
  std::vector<size_t> rows;
  std::vector<double> y;
  for (size_t r = 0; r < d.rows(); ++r) {
    if (d.dv.missing(r)) {
      ++m.missing;
      continue;
    }
    const double v = d.dv.value[r];
    if (o.family == Family::binomial && v != 0 && v != 1)
      return row_error(d, r, d.dv_name, "the binomial family needs 0 or 1 in every row, found " + std::to_string(v));
    if (o.transform == Transform::log && !(v > 0))
      return row_error(d, r, d.dv_name, "--transform log needs values above 0, found " + std::to_string(v));
    rows.push_back(r);
    y.push_back(o.transform == Transform::log ? std::log(v) : o.family == Family::binomial ? v : d.dv.delta[r]);
  }
  if (rows.empty()) return Error{d.source, 0, 0, d.dv_name, "no row has a dv value"};
  if (o.transform == Transform::none && o.family == Family::gaussian) m.y_offset = d.dv.offset;
  if (auto s = check_between(d, rows); !s) return s.error();
  std::vector<CodedFactor> factors;
  auto add = [&](const Factor& f, bool within) -> Status {
    std::vector<std::string> labels;
    for (size_t r : rows) labels.push_back(f.level[r]);
    factors.push_back(code_factor(f.name, labels, within));
    if (factors.back().levels.size() < 2)
      return Error{d.source, 0, 0, f.name, "factor has one level in the rows used; a factor needs two or more"};
    return {};
  };
  for (const auto& f : d.within)
    if (auto s = add(f, true); !s) return s.error();
  for (const auto& f : d.between)
    if (auto s = add(f, false); !s) return s.error();
  m.design = fixed_design(std::move(factors));
  if (m.design.factors.empty()) {
    m.design.X = Eigen::MatrixXd::Ones(static_cast<Eigen::Index>(rows.size()), 1);
  }
  if (auto s = check_cells(m.design, d.source); !s) return s.error();
  m.y = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  std::vector<std::string> labels;
  for (size_t r : rows) labels.push_back(d.subject[r]);
  m.groupings.push_back(make_grouping(data.subject_name, labels));
  if (!data.item_name.empty()) {
    labels.clear();
    for (size_t r : rows) labels.push_back(data.item[r]);
    m.groupings.push_back(make_grouping(data.item_name, labels));
  }
  for (const auto& g : m.groupings) {
    if (g.levels.size() < 2)
      return Error{d.source, 0, 0, g.name, "grouping factors must have > 1 sampled level (lme4)"};
    if (g.levels.size() >= rows.size())
      return Error{d.source, 0, 0, g.name,
                   "number of levels of each grouping factor must be < number of observations (lme4)"};
    m.varies.push_back(varies_within(g, m.design.factors));
  }
  const std::string dv = r_name(d.dv_name);
  m.dv_expr = o.transform == Transform::log ? "log(" + dv + ")" : dv;
  return m;
}

std::vector<FormulaTerm> random_structure(const PreparedModel& m, RandomEffects random,
                                          std::vector<std::string>& notes) {
  std::vector<FormulaTerm> terms;
  const size_t n = static_cast<size_t>(m.y.size());
  for (size_t g = 0; g < m.groupings.size(); ++g) {
    FormulaTerm t{static_cast<int>(g), {0}, true};
    std::vector<const FixedTerm*> slopes;
    for (const auto& ft : m.design.terms) {
      bool all = true;
      for (int f : ft.factors) all = all && m.varies[g][static_cast<size_t>(f)];
      const bool main = ft.factors.size() == 1;
      if (all && ((random == RandomEffects::slopes && g == 0 && main) || random == RandomEffects::maximal))
        slopes.push_back(&ft);
    }
    const size_t nl = m.groupings[g].levels.size();
    auto width = [&] {
      size_t k = 1;
      for (const auto* s : slopes) k += s->columns.size();
      return k;
    };
    while (!slopes.empty() && nl * width() >= n) {
      notes.push_back("dropped the by-" + m.groupings[g].name + " slope of " + slopes.back()->name + ": " +
                      std::to_string(nl) + " levels x " + std::to_string(width()) +
                      " random effects are not fewer than the " + std::to_string(n) + " rows");
      slopes.pop_back();
    }
    for (const auto* s : slopes) t.columns.insert(t.columns.end(), s->columns.begin(), s->columns.end());
    terms.push_back(t);
  }
  return terms;
}

std::vector<RandomTerm> expand_terms(const std::vector<FormulaTerm>& terms, const std::vector<Grouping>& groupings) {
  std::vector<RandomTerm> out;
  for (const auto& t : terms) {
    if (t.correlated) {
      out.push_back({t.grouping, t.columns});
    } else {
      for (int c : t.columns) out.push_back({t.grouping, {c}});
    }
  }
  return lme4_term_order(std::move(out), groupings);
}

std::string lme4_formula(const PreparedModel& m, const std::vector<FormulaTerm>& terms) {
  std::string f = m.dv_expr + " ~ ";
  if (m.design.factors.empty()) f += "1";
  for (size_t i = 0; i < m.design.factors.size(); ++i) f += (i ? " * " : "") + r_name(m.design.factors[i].name);
  for (const auto& t : terms) {
    std::string lhs;
    if (t.correlated) {
      const std::set<int> cols(t.columns.begin(), t.columns.end());
      lhs = cols.count(0) ? "1" : "0";
      for (const auto& ft : m.design.terms) {
        bool in = true;
        for (int c : ft.columns) in = in && cols.count(c);
        if (!in) continue;
        std::string name;
        for (size_t k = 0; k < ft.factors.size(); ++k)
          name += (k ? ":" : "") + r_name(m.design.factors[static_cast<size_t>(ft.factors[k])].name);
        lhs += " + " + name;
      }
    } else {
      lhs = std::find(t.columns.begin(), t.columns.end(), 0) != t.columns.end() ? "1" : "0";
      for (int c : t.columns)
        if (c != 0) lhs += " + " + re_column_name(m, c);
    }
    const bool split = !t.correlated && t.columns.size() > 1;
    f += " + (" + lhs + (split ? " || " : " | ") + r_name(m.groupings[static_cast<size_t>(t.grouping)].name) + ")";
  }
  return f;
}

std::string r_code(const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmOptions& o) {
  std::string s;
  s += "library(lmerTest)  # lme4 with Satterthwaite df\n";
  s += "options(contrasts = c(\"contr.sum\", \"contr.poly\"))\n";
  s += "# d: a data frame of the rows dtlab used, e.g. d <- read.csv(\"trials.csv\")\n";
  for (const auto& f : m.design.factors) {
    std::string levels;
    for (const auto& l : f.levels) {
      std::string q;
      for (char c : l) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
      levels += (levels.empty() ? "\"" : ", \"") + q + "\"";
    }
    s += "d$" + r_name(f.name) + " <- factor(d$" + r_name(f.name) + ", levels = c(" + levels + "))\n";
  }
  for (const auto& g : m.groupings) s += "d$" + r_name(g.name) + " <- factor(d$" + r_name(g.name) + ")\n";
  std::set<int> numeric;
  for (const auto& t : terms)
    if (!t.correlated)
      for (int c : t.columns)
        if (c != 0) numeric.insert(c);
  if (!numeric.empty()) {
    std::string rhs;
    for (size_t i = 0; i < m.design.factors.size(); ++i) rhs += (i ? " * " : "") + r_name(m.design.factors[i].name);
    s += "X <- model.matrix(~ " + rhs + ", d)  # the contr.sum columns, for the || terms\n";
    for (int c : numeric)
      s += "d$" + re_column_name(m, c) + " <- X[, \"" + m.design.column_names[static_cast<size_t>(c)] + "\"]\n";
  }
  const std::string formula = lme4_formula(m, terms);
  if (o.family == Family::binomial) {
    // glmer's defaults stop short of the Laplace optimum (PIRLS at 1e-7, Nelder-Mead at FtolAbs 1e-5)
    const std::string tight =
        "glmerControl(tolPwrss = 1e-13, optimizer = \"nloptwrap\", optCtrl = list(xtol_abs = 1e-14, "
        "ftol_abs = 1e-15, xtol_rel = 1e-14, maxeval = 1e5))";
    s += "ctl <- " + tight + "  # to the optimum, as dtlab\n";
    s += "m <- glmer(" + formula + ", data = d, family = binomial, control = ctl)\n";
    s += "summary(m)\n";
    s += "afex::mixed(" + formula + ", data = d, family = binomial, method = \"LRT\", control = ctl)  # LRT of each term\n";
    for (const auto& f : m.design.factors)
      s += "emmeans::emmeans(m, pairwise ~ " + r_name(f.name) + ", adjust = \"holm\", type = \"response\")\n";
  } else {
    s += "m <- lmer(" + formula + ", data = d, REML = " + (o.reml ? "TRUE" : "FALSE") + ")\n";
    s += "summary(m)\n";
    s += o.ddf == DenominatorDf::kenward_roger ? "anova(m, ddf = \"Kenward-Roger\")\n" : "anova(m)\n";
    for (const auto& f : m.design.factors) {
      s += "emmeans::emmeans(m, pairwise ~ " + r_name(f.name) +
           ", adjust = \"holm\", lmer.df = \"satterthwaite\", lmerTest.limit = Inf";
      s += o.transform == Transform::log ? ", type = \"response\")\n" : ")\n";
    }
  }
  return s;
}

}  // namespace dtlab::stats::detail
