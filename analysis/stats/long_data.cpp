// Building LongData from CSV tables; see long_data.h.
#include "analysis/stats/long_data.h"

#include <algorithm>
#include <cctype>
#include <optional>

#include "analysis/stats/select.h"  // column_list

namespace dtlab::stats {
namespace {

Result<int> find_column(const CsvTable& t, const std::string& name, const char* role) {
  const int c = t.column(name);
  if (c < 0)
    return Error{t.file, 1, 0, name_for_message(name),
                 std::string("no such column for ") + role + "; the header has: " + column_list(t)};
  return c;
}

// Parses one dv cell; nullopt = missing. Errors name file, line, column.
Result<std::optional<Decimal>> numeric_cell(const CsvTable& t, size_t row, int col) {
  const std::string& cell = t.rows[row][static_cast<size_t>(col)];
  if (is_missing_token(cell)) return std::optional<Decimal>{};
  if (auto d = parse_decimal(cell)) return std::optional<Decimal>{*d};
  std::string lower = cell;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::string hint = "expected a number (leave the cell empty or write NA for a missing value)";
  if (lower == "nan" || lower == "inf" || lower == "-inf" || lower == "+inf" || lower == "infinity")
    hint = "NaN and Inf are not accepted as data: " + hint;
  return Error{t.file, t.line[row], col + 1, name_for_message(t.header[static_cast<size_t>(col)]),
               hint + ", found " + quote_text(cell)};
}

Status check_label(const CsvTable& t, size_t row, int col, const char* what) {
  if (is_missing_token(t.rows[row][static_cast<size_t>(col)]))
    return Error{t.file, t.line[row], col + 1, name_for_message(t.header[static_cast<size_t>(col)]),
                 std::string("empty or NA ") + what + ": every row needs one"};
  return {};
}

Status check_distinct(const std::vector<std::string>& names, const std::string& file) {
  for (size_t i = 0; i < names.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (names[i] == names[j]) return Error{file, 0, 0, name_for_message(names[i]), "column given for two roles"};
  return {};
}

}  // namespace

bool is_missing_token(const std::string& cell) { return cell.empty() || cell == "NA"; }

std::string LongData::where(size_t row) const {
  if (!source.empty() && row < line.size() && line[row] > 0) return source + ":" + std::to_string(line[row]);
  return "row " + std::to_string(row + 1);
}

Result<LongData> long_data_from_csv(const CsvTable& t, const ColumnRoles& roles) {
  std::vector<std::string> used{roles.dv};
  if (!roles.subject.empty()) used.push_back(roles.subject);
  used.insert(used.end(), roles.within.begin(), roles.within.end());
  used.insert(used.end(), roles.between.begin(), roles.between.end());
  if (auto s = check_distinct(used, t.file); !s) return s.error();

  auto dv_col = find_column(t, roles.dv, "the dependent variable (--dv)");
  if (!dv_col) return dv_col.error();
  int subject_col = -1;
  if (!roles.subject.empty()) {
    auto c = find_column(t, roles.subject, "the subject id (--subject)");
    if (!c) return c.error();
    subject_col = *c;
  }
  std::vector<int> within_cols, between_cols;
  for (const auto& w : roles.within) {
    auto c = find_column(t, w, "a within-subject factor (--within)");
    if (!c) return c.error();
    within_cols.push_back(*c);
  }
  for (const auto& b : roles.between) {
    auto c = find_column(t, b, "a between-subject factor (--between)");
    if (!c) return c.error();
    between_cols.push_back(*c);
  }

  LongData d;
  d.source = t.file;
  d.line = t.line;
  d.dv_name = roles.dv;
  d.within.resize(roles.within.size());
  d.between.resize(roles.between.size());
  for (size_t f = 0; f < roles.within.size(); ++f) d.within[f].name = roles.within[f];
  for (size_t f = 0; f < roles.between.size(); ++f) d.between[f].name = roles.between[f];
  std::vector<std::optional<Decimal>> values;
  values.reserve(t.rows.size());
  for (size_t r = 0; r < t.rows.size(); ++r) {
    auto v = numeric_cell(t, r, *dv_col);
    if (!v) return v.error();
    values.push_back(*v);
    if (subject_col >= 0) {
      if (auto s = check_label(t, r, subject_col, "subject id"); !s) return s.error();
      d.subject.push_back(t.rows[r][static_cast<size_t>(subject_col)]);
    }
    for (size_t f = 0; f < within_cols.size(); ++f) {
      if (auto s = check_label(t, r, within_cols[f], "factor level"); !s) return s.error();
      d.within[f].level.push_back(t.rows[r][static_cast<size_t>(within_cols[f])]);
    }
    for (size_t f = 0; f < between_cols.size(); ++f) {
      if (auto s = check_label(t, r, between_cols[f], "factor level"); !s) return s.error();
      d.between[f].level.push_back(t.rows[r][static_cast<size_t>(between_cols[f])]);
    }
  }
  if (t.rows.empty()) return Error{t.file, 0, 0, "", "the file has a header but no data rows"};
  d.dv = Measurements::from_decimals(values);
  return d;
}

Result<LongData> long_data_from_wide_csv(const CsvTable& t, const WideRoles& roles) {
  int subject_col = -1;
  if (!roles.subject.empty()) {
    auto c = find_column(t, roles.subject, "the subject id (--subject)");
    if (!c) return c.error();
    subject_col = *c;
  }
  std::vector<int> between_cols;
  for (const auto& b : roles.between) {
    auto c = find_column(t, b, "a between-subject factor (--between)");
    if (!c) return c.error();
    between_cols.push_back(*c);
  }
  std::vector<int> cond_cols;
  if (roles.conditions.empty()) {
    for (size_t c = 0; c < t.header.size(); ++c) {
      const int ci = static_cast<int>(c);
      if (ci != subject_col && !t.header[c].empty() &&
          std::find(between_cols.begin(), between_cols.end(), ci) == between_cols.end())
        cond_cols.push_back(ci);
    }
  } else {
    for (const auto& name : roles.conditions) {
      auto c = find_column(t, name, "a condition");
      if (!c) return c.error();
      cond_cols.push_back(*c);
    }
  }
  if (cond_cols.empty()) return Error{t.file, 1, 0, "", "no condition columns in the wide table"};
  if (t.rows.empty()) return Error{t.file, 0, 0, "", "the file has a header but no data rows"};

  LongData d;
  d.source = t.file;
  d.dv_name = roles.dv;
  Factor cond{roles.factor, {}};
  d.between.resize(roles.between.size());
  for (size_t f = 0; f < roles.between.size(); ++f) d.between[f].name = roles.between[f];
  std::vector<std::optional<Decimal>> values;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    std::string id;
    if (subject_col >= 0) {
      if (auto s = check_label(t, r, subject_col, "subject id"); !s) return s.error();
      id = t.rows[r][static_cast<size_t>(subject_col)];
    } else {
      id = "line " + std::to_string(t.line[r]);
    }
    for (size_t f = 0; f < between_cols.size(); ++f)
      if (auto s = check_label(t, r, between_cols[f], "factor level"); !s) return s.error();
    for (int c : cond_cols) {
      auto v = numeric_cell(t, r, c);
      if (!v) return v.error();
      if (roles.conditions_are_groups && !v->has_value()) continue;  // a ragged group column
      values.push_back(*v);
      d.line.push_back(t.line[r]);
      if (!roles.conditions_are_groups) d.subject.push_back(id);
      cond.level.push_back(t.header[static_cast<size_t>(c)]);
      for (size_t f = 0; f < between_cols.size(); ++f)
        d.between[f].level.push_back(t.rows[r][static_cast<size_t>(between_cols[f])]);
    }
  }
  if (roles.conditions_are_groups)
    d.between.insert(d.between.begin(), std::move(cond));
  else
    d.within.push_back(std::move(cond));
  d.dv = Measurements::from_decimals(values);
  return d;
}

}  // namespace dtlab::stats
