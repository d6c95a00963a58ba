// Subject x cell matrix with listwise deletion; see design.h.
#include "analysis/stats/detail/design.h"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace dtlab::stats::detail {
namespace {

size_t index_of(std::vector<std::string>& levels, std::map<std::string, size_t>& lookup, const std::string& s) {
  auto [it, inserted] = lookup.emplace(s, levels.size());
  if (inserted) levels.push_back(s);
  return it->second;
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
  for (size_t f = 0; f < lv.size(); ++f) s += (f ? ", " : "") + within_names[f] + "=" + within_levels[f][lv[f]];
  return s.empty() ? "(all)" : s;
}

std::string CellDesign::cell_name(size_t cell) const {
  const auto lv = cell_levels(cell);
  std::string s;
  for (size_t f = 0; f < lv.size(); ++f) s += (f ? ":" : "") + within_levels[f][lv[f]];
  return s;
}

Result<CellDesign> build_cell_design(const LongData& data) {
  const size_t n = data.rows();
  if (data.subject.size() != n) throw std::invalid_argument("build_cell_design: one subject id per row is required");
  for (const auto& f : data.within)
    if (f.level.size() != n) throw std::invalid_argument("build_cell_design: factor '" + f.name + "' needs one level per row");
  for (const auto& f : data.between)
    if (f.level.size() != n) throw std::invalid_argument("build_cell_design: factor '" + f.name + "' needs one level per row");

  CellDesign d;
  d.offset = data.dv.offset;
  const size_t nw = data.within.size(), nb = data.between.size();
  d.within_levels.resize(nw);
  d.between_levels.resize(nb);
  for (const auto& f : data.within) d.within_names.push_back(f.name);
  for (const auto& f : data.between) d.between_names.push_back(f.name);
  std::vector<std::map<std::string, size_t>> wl(nw), bl(nb);
  std::map<std::string, size_t> subject_lookup;
  std::vector<std::string> subjects;
  std::vector<size_t> row_subject(n), row_cell(n, 0);
  std::vector<std::vector<size_t>> row_group(n, std::vector<size_t>(nb));
  for (size_t r = 0; r < n; ++r) {
    row_subject[r] = index_of(subjects, subject_lookup, data.subject[r]);
    for (size_t f = 0; f < nw; ++f) index_of(d.within_levels[f], wl[f], data.within[f].level[r]);
    for (size_t f = 0; f < nb; ++f) row_group[r][f] = index_of(d.between_levels[f], bl[f], data.between[f].level[r]);
  }
  for (const auto& lv : d.within_levels) d.cells *= lv.size();
  for (size_t r = 0; r < n; ++r) {
    size_t c = 0;
    for (size_t f = 0; f < nw; ++f) c = c * d.within_levels[f].size() + wl[f].at(data.within[f].level[r]);
    row_cell[r] = c;
  }

  const size_t ns = subjects.size();
  std::vector<std::vector<double>> sum_delta(ns, std::vector<double>(d.cells, 0.0));
  std::vector<std::vector<double>> sum_value = sum_delta;
  std::vector<std::vector<size_t>> count(ns, std::vector<size_t>(d.cells, 0));
  std::vector<std::vector<bool>> has_missing(ns, std::vector<bool>(d.cells, false));
  std::vector<long> group_row(ns, -1);
  for (size_t r = 0; r < n; ++r) {
    const size_t s = row_subject[r], c = row_cell[r];
    if (group_row[s] < 0) {
      group_row[s] = static_cast<long>(r);
    } else {
      const size_t r0 = static_cast<size_t>(group_row[s]);
      for (size_t f = 0; f < nb; ++f)
        if (row_group[r][f] != row_group[r0][f])
          return Error{data.source, r < data.line.size() ? data.line[r] : 0, 0, data.between[f].name,
                       "subject '" + subjects[s] + "' has level '" + data.between[f].level[r] + "' here but '" +
                           data.between[f].level[r0] + "' at " + data.where(r0) +
                           "; a between-subject factor must be constant within a subject"};
    }
    if (data.dv.missing(r)) {
      has_missing[s][c] = true;
      continue;
    }
    sum_delta[s][c] += data.dv.delta[r];
    sum_value[s][c] += data.dv.value[r];
    ++count[s][c];
  }

  size_t averaged = 0;
  std::string dropped_text;
  for (size_t s = 0; s < ns; ++s) {
    size_t first_missing = d.cells;
    for (size_t c = 0; c < d.cells && first_missing == d.cells; ++c)
      if (count[s][c] == 0 || has_missing[s][c]) first_missing = c;
    if (first_missing < d.cells) {
      d.dropped.push_back(subjects[s]);
      dropped_text += (dropped_text.empty() ? "" : "; ") + subjects[s] + " (" + d.cell_label(first_missing) + ")";
      continue;
    }
    std::vector<double> dl(d.cells), vl(d.cells);
    for (size_t c = 0; c < d.cells; ++c) {
      if (count[s][c] > 1) ++averaged;
      dl[c] = count[s][c] == 1 ? sum_delta[s][c] : sum_delta[s][c] / static_cast<double>(count[s][c]);
      vl[c] = count[s][c] == 1 ? sum_value[s][c] : sum_value[s][c] / static_cast<double>(count[s][c]);
    }
    d.subjects.push_back(subjects[s]);
    d.delta.push_back(std::move(dl));
    d.value.push_back(std::move(vl));
    d.group.push_back(row_group[static_cast<size_t>(group_row[s])]);
  }
  if (!d.dropped.empty())
    d.warnings.push_back("listwise deletion: removed " + std::to_string(d.dropped.size()) +
                         " subject(s) with a missing cell (first missing cell in parentheses): " + dropped_text);
  if (averaged > 0)
    d.warnings.push_back(std::to_string(averaged) +
                         " subject x cell combination(s) had more than one row; each was replaced by the mean of its rows");
  return d;
}

}  // namespace dtlab::stats::detail
