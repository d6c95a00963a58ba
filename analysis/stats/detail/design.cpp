// Subject x cell matrix with listwise deletion; see design.h.
#include "analysis/stats/detail/design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include "analysis/stats/csv.h"
#include "analysis/stats/detail/sum.h"

namespace dtlab::stats::detail {
namespace {

constexpr size_t kNone = std::numeric_limits<size_t>::max();

// Levels of one column in first-appearance order; the map keys view the
// caller's strings, which outlive it.
struct Index {
  std::vector<std::string> names;
  std::unordered_map<std::string_view, size_t> lookup;

  size_t of(const std::string& s) {
    auto [it, inserted] = lookup.emplace(s, names.size());
    if (inserted) names.push_back(s);
    return it->second;
  }
};

// One slot per subject x cell: the rows that fell into it.
struct Slots {
  std::vector<size_t> count, first;          // rows in the slot, the first of them
  std::vector<char> missing;                 // a row of the slot has a missing dv
  std::vector<size_t> group_row;             // per subject: the row that set its between levels
  std::vector<std::vector<size_t>> rows_of;  // per slot, filled only when some slot has several rows
};

double row_noise(const Measurements& dv, size_t r) {
  if (r < dv.noise.size()) return dv.noise[r];
  return std::ldexp(std::fabs(dv.delta[r]), -53);
}

// Mean of x: compensated sum / n, or the sum of x / n where the sum overflows.
double mean_of(const std::vector<double>& x) {
  Sum s;
  for (double v : x) s.add(v);
  const double n = static_cast<double>(x.size());
  if (std::isfinite(s.value())) return s.value() / n;
  double m = 0;
  for (double v : x) m += v / n;
  return m;
}

double median_of(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t h = x.size() / 2;
  return x.size() % 2 ? x[h] : x[h - 1] / 2 + x[h] / 2;
}

// One value from several: on the decimal digits when `decimals` is given
// (result in *exact_value), else on the doubles.
struct Reduced {
  double delta = 0, value = 0, noise = 0;
  std::optional<Decimal> decimal;
};

Reduced reduce_values(const Measurements& dv, const std::vector<Decimal>& decimals, const std::vector<double>& deltas,
                      const std::vector<double>& values, double worst_noise, bool median) {
  Reduced r;
  if (!decimals.empty()) r.decimal = median ? decimal_median(decimals) : decimal_mean(decimals);
  if (r.decimal) {
    dv.describe(*r.decimal, r.value, r.delta, r.noise);
    r.noise += worst_noise;
    return r;
  }
  r.delta = median ? median_of(deltas) : mean_of(deltas);
  r.value = median ? median_of(values) : mean_of(values);
  r.noise = worst_noise + std::ldexp(std::fabs(r.delta), -52);  // the division's rounding
  return r;
}

// One value from the several rows of a subject x cell (only with an aggregation).
Reduced reduce(const LongData& data, const std::vector<size_t>& rows) {
  std::vector<double> d, v;
  std::vector<Decimal> dec;
  double worst = 0;
  for (size_t r : rows) {
    d.push_back(data.dv.delta[r]);
    v.push_back(data.dv.value[r]);
    if (!data.dv.decimal.empty()) dec.push_back(data.dv.decimal[r]);
    worst = std::max(worst, row_noise(data.dv, r));
  }
  return reduce_values(data.dv, dec, d, v, worst, data.aggregate == Aggregate::median);
}

}  // namespace

std::vector<size_t> CellDesign::cell_levels(size_t cell) const {
  std::vector<size_t> lv(within_levels.size());
  for (size_t f = within_levels.size(); f-- > 0;) {
    lv[f] = cell % within_levels[f].size();
    cell /= within_levels[f].size();
  }
  return lv;
}

std::string CellDesign::cell_label(size_t cell) const {
  const auto lv = cell_levels(cell);
  std::string s;
  for (size_t f = 0; f < lv.size(); ++f)
    s += (f ? ", " : "") + name_for_message(within_names[f]) + "=" + name_for_message(within_levels[f][lv[f]]);
  return s.empty() ? "(all)" : s;
}

std::string CellDesign::cell_name(size_t cell) const {
  const auto lv = cell_levels(cell);
  std::string s;
  for (size_t f = 0; f < lv.size(); ++f) s += (f ? ":" : "") + within_levels[f][lv[f]];
  return s;
}

CellMean subject_mean(const CellDesign& d, size_t s, const std::vector<size_t>& cells) {
  if (cells.size() == 1) return {d.value[s][cells[0]], d.delta[s][cells[0]]};
  std::vector<double> dl, vl;
  std::vector<Decimal> dec;
  for (size_t c : cells) {
    dl.push_back(d.delta[s][c]);
    vl.push_back(d.value[s][c]);
    if (!d.decimal.empty()) dec.push_back(d.decimal[s][c]);
  }
  const Reduced r = reduce_values(d.dv_scale, dec, dl, vl, 0.0, false);
  return {r.value, r.delta};
}

FactorMarginals factor_marginals(const CellDesign& d, size_t f) {
  const size_t L = d.within_levels[f].size(), N = d.subjects.size();
  FactorMarginals m{std::vector<std::vector<double>>(L, std::vector<double>(N, 0.0)),
                    std::vector<std::vector<double>>(L, std::vector<double>(N, 0.0))};
  std::vector<std::vector<size_t>> cells(L);
  for (size_t c = 0; c < d.cells; ++c) cells[d.cell_levels(c)[f]].push_back(c);
  for (size_t l = 0; l < L; ++l)
    for (size_t s = 0; s < N; ++s) {
      const CellMean cm = subject_mean(d, s, cells[l]);
      m.value[l][s] = cm.value;
      m.delta[l][s] = cm.delta;
    }
  return m;
}

std::string name_list(const std::vector<std::string>& names, size_t shown) {
  std::string s;
  for (size_t i = 0; i < names.size() && i < shown; ++i) s += (i ? "; " : "") + name_for_message(names[i]);
  if (names.size() > shown) s += "; and " + std::to_string(names.size() - shown) + " more";
  return s;
}

namespace {

// Every row's subject, within levels and between levels, as indices in first-appearance order.
struct Rows {
  Index subjects;
  std::vector<size_t> subject, within, group;  // within: n x nw, group: n x nb
};

Rows index_rows(const LongData& data, CellDesign& d) {
  const size_t n = data.rows(), nw = data.within.size(), nb = data.between.size();
  Rows rows;
  rows.subject.resize(n);
  rows.within.resize(n * nw);
  rows.group.resize(n * nb);
  std::vector<Index> wl(nw), bl(nb);
  for (size_t r = 0; r < n; ++r) {
    rows.subject[r] = rows.subjects.of(data.subject[r]);
    for (size_t f = 0; f < nw; ++f) rows.within[r * nw + f] = wl[f].of(data.within[f].level[r]);
    for (size_t f = 0; f < nb; ++f) rows.group[r * nb + f] = bl[f].of(data.between[f].level[r]);
  }
  for (size_t f = 0; f < nw; ++f) d.within_levels.push_back(wl[f].names);
  for (size_t f = 0; f < nb; ++f) d.between_levels.push_back(bl[f].names);
  for (const auto& lv : d.within_levels) d.cells *= lv.size();
  return rows;
}

// Which rows fall into each subject x cell slot; Errors for a between level
// changing within a subject and for a repeated slot without an aggregation.
Result<Slots> fill_slots(const LongData& data, const CellDesign& d, const Rows& rows) {
  const size_t n = data.rows(), nw = data.within.size(), nb = data.between.size();
  const size_t C = d.cells, ns = rows.subjects.names.size();
  Slots slots{std::vector<size_t>(ns * C, 0), std::vector<size_t>(ns * C, kNone), std::vector<char>(ns * C, 0),
              std::vector<size_t>(ns, kNone), {}};
  std::vector<size_t> row_slot(n);
  bool repeated = false;
  for (size_t r = 0; r < n; ++r) {
    const size_t s = rows.subject[r];
    size_t c = 0;
    for (size_t f = 0; f < nw; ++f) c = c * d.within_levels[f].size() + rows.within[r * nw + f];
    const size_t k = s * C + c;
    row_slot[r] = k;
    const int line = r < data.line.size() ? data.line[r] : 0;
    if (slots.group_row[s] == kNone) {
      slots.group_row[s] = r;
    } else {
      const size_t r0 = slots.group_row[s];
      for (size_t f = 0; f < nb; ++f)
        if (rows.group[r * nb + f] != rows.group[r0 * nb + f])
          return Error{data.source, line, 0, name_for_message(data.between[f].name),
                       "subject " + quote_text(rows.subjects.names[s]) + " has level " +
                           quote_text(data.between[f].level[r]) + " here but " + quote_text(data.between[f].level[r0]) +
                           " at " + data.where(r0) + "; a between-subject factor must be constant within a subject"};
    }
    if (slots.count[k] > 0 && data.aggregate == Aggregate::none)
      return Error{data.source, line, 0, "",
                   "subject " + quote_text(rows.subjects.names[s]) + " has a second row for the cell " + d.cell_label(c) +
                       " (the first is at " + data.where(slots.first[k]) +
                       "): expected one value per subject and cell; select rows (dtlab stats --where) or reduce them "
                       "to their mean or median (--aggregate mean|median)"};
    if (slots.first[k] == kNone) slots.first[k] = r;
    ++slots.count[k];
    repeated = repeated || slots.count[k] > 1;
    if (data.dv.missing(r)) slots.missing[k] = 1;
  }
  if (repeated) {
    slots.rows_of.resize(ns * C);
    for (size_t r = 0; r < n; ++r) slots.rows_of[row_slot[r]].push_back(r);
  }
  return slots;
}

// The subjects with every cell, their cell values, and the warnings naming the others.
void keep_complete(const LongData& data, CellDesign& d, const Rows& rows, const Slots& slots) {
  const size_t C = d.cells, nb = data.between.size();
  size_t aggregated = 0;
  bool all_decimal = !data.dv.decimal.empty();
  std::vector<std::string> dropped_text;
  for (size_t s = 0; s < rows.subjects.names.size(); ++s) {
    size_t first_missing = C;
    for (size_t c = 0; c < C && first_missing == C; ++c)
      if (slots.count[s * C + c] == 0 || slots.missing[s * C + c]) first_missing = c;
    if (first_missing < C) {
      d.dropped.push_back(rows.subjects.names[s]);
      if (dropped_text.size() < 10)
        dropped_text.push_back(name_for_message(rows.subjects.names[s]) + " (" + d.cell_label(first_missing) + ")");
      continue;
    }
    std::vector<double> dl(C), vl(C), nl(C);
    std::vector<Decimal> dec(data.dv.decimal.empty() ? 0 : C);
    bool decimal = !dec.empty();
    for (size_t c = 0; c < C; ++c) {
      const size_t k = s * C + c;
      if (slots.count[k] > 1) {
        ++aggregated;
        const Reduced r = reduce(data, slots.rows_of[k]);
        dl[c] = r.delta;
        vl[c] = r.value;
        nl[c] = r.noise;
        if (r.decimal) dec[c] = *r.decimal;
        else decimal = false;
      } else {
        const size_t r = slots.first[k];
        dl[c] = data.dv.delta[r];
        vl[c] = data.dv.value[r];
        nl[c] = row_noise(data.dv, r);
        if (decimal) dec[c] = data.dv.decimal[r];
      }
    }
    if (!decimal) all_decimal = false;
    d.subjects.push_back(rows.subjects.names[s]);
    d.delta.push_back(std::move(dl));
    d.value.push_back(std::move(vl));
    d.noise.push_back(std::move(nl));
    d.decimal.push_back(std::move(dec));
    std::vector<size_t> g(nb);
    for (size_t f = 0; f < nb; ++f) g[f] = rows.group[slots.group_row[s] * nb + f];
    d.group.push_back(std::move(g));
  }
  if (!all_decimal) d.decimal.clear();  // one cell without its decimal: every mean is taken on the doubles
  if (!d.dropped.empty()) {
    std::string text;
    for (const auto& t : dropped_text) text += (text.empty() ? "" : "; ") + t;
    if (d.dropped.size() > dropped_text.size())
      text += "; and " + std::to_string(d.dropped.size() - dropped_text.size()) + " more";
    d.warnings.push_back("listwise deletion: removed " + std::to_string(d.dropped.size()) +
                         (d.dropped.size() == 1 ? " subject" : " subjects") +
                         " with a missing cell (first missing cell in parentheses): " + text);
  }
  if (aggregated > 0)
    d.warnings.push_back(std::to_string(aggregated) + " subject x cell combination" + (aggregated == 1 ? "" : "s") +
                         " had more than one row; each was replaced by the " +
                         (data.aggregate == Aggregate::median ? "median" : "mean") + " of its rows (as requested)");
}

}  // namespace

Result<CellDesign> build_cell_design(const LongData& data) {
  const size_t n = data.rows();
  if (data.subject.size() != n) throw std::invalid_argument("build_cell_design: one subject id per row is required");
  for (const auto& f : data.within)
    if (f.level.size() != n) throw std::invalid_argument("build_cell_design: factor '" + f.name + "' needs one level per row");
  for (const auto& f : data.between)
    if (f.level.size() != n) throw std::invalid_argument("build_cell_design: factor '" + f.name + "' needs one level per row");
  CellDesign d;
  d.offset = data.dv.offset;
  d.dv_scale.offset = data.dv.offset;
  d.dv_scale.offset_decimal = data.dv.offset_decimal;
  for (const auto& f : data.within) d.within_names.push_back(f.name);
  for (const auto& f : data.between) d.between_names.push_back(f.name);
  const Rows rows = index_rows(data, d);
  auto slots = fill_slots(data, d, rows);
  if (!slots) return slots.error();
  keep_complete(data, d, rows, *slots);
  return d;
}

}  // namespace dtlab::stats::detail
