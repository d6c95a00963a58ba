// Row selection before a test; see select.h.
#include "analysis/stats/select.h"

#include <optional>

namespace dtlab::stats {
namespace {

std::optional<bool> practice_flag(const std::string& cell) {
  if (cell.empty() || cell == "NA" || cell == "0" || cell == "false" || cell == "FALSE" || cell == "no") return false;
  if (cell == "1" || cell == "true" || cell == "TRUE" || cell == "yes") return true;
  return std::nullopt;
}

std::string rows_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " row" : " rows"); }

}  // namespace

std::string column_list(const CsvTable& t) {
  std::string s;
  for (size_t i = 0; i < t.header.size() && i < 40; ++i) s += (i ? ", " : "") + name_for_message(t.header[i]);
  if (t.header.size() > 40) s += ", and " + std::to_string(t.header.size() - 40) + " more";
  return s;
}

Result<RowCondition> parse_row_condition(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0 || (eq == 1 && text[0] == '!'))
    return Error{"", 0, 0, "--where", "expected COL=VALUE or COL!=VALUE, got " + quote_text(text)};
  RowCondition c;
  c.equal = text[eq - 1] != '!';
  c.column = std::string(text.substr(0, c.equal ? eq : eq - 1));
  c.value = std::string(text.substr(eq + 1));
  return c;
}

Result<SelectionReport> select_rows(CsvTable& t, const RowSelection& sel) {
  SelectionReport r;
  r.read = t.rows.size();
  std::vector<int> where_cols;
  for (const auto& c : sel.where) {
    const int col = t.column(c.column);
    if (col < 0)
      return Error{t.file, 1, 0, name_for_message(c.column), "no such column for --where; the header has: " + column_list(t)};
    where_cols.push_back(col);
  }
  const int practice = t.column("practice"), excluded = t.column("excluded");
  r.practice_column = practice >= 0;
  r.excluded_column = excluded >= 0;
  r.dtlab_export = practice >= 0 && t.column("trial_seed") >= 0 && t.column("protocol_sha256") >= 0;
  if (sel.practice == Practice::exclude && practice < 0)
    return Error{t.file, 1, 0, "practice", "--exclude-practice needs a column named practice; the header has: " + column_list(t)};
  r.practice_excluded = practice >= 0 && (sel.practice == Practice::exclude ||
                                          (sel.practice == Practice::automatic && r.dtlab_export));

  std::vector<std::vector<std::string>> rows;
  std::vector<int> lines;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& row = t.rows[i];
    if (r.practice_excluded) {
      const auto flag = practice_flag(row[static_cast<std::size_t>(practice)]);
      if (!flag)
        return Error{t.file, t.line[i], practice + 1, "practice",
                     "expected 1/0, true/false or yes/no, found " + quote_text(row[static_cast<std::size_t>(practice)])};
      if (*flag) {
        ++r.practice_left_out;
        continue;
      }
    }
    if (excluded >= 0 && !sel.with_excluded) {
      const std::string& cell = row[static_cast<std::size_t>(excluded)];
      if (!cell.empty() && cell != "NA") {
        ++r.excluded_left_out;
        continue;
      }
    }
    bool keep = true;
    for (std::size_t k = 0; k < sel.where.size() && keep; ++k)
      keep = (row[static_cast<std::size_t>(where_cols[k])] == sel.where[k].value) == sel.where[k].equal;
    if (!keep) {
      ++r.where_left_out;
      continue;
    }
    rows.push_back(row);
    lines.push_back(t.line[i]);
  }
  t.rows = std::move(rows);
  t.line = std::move(lines);
  r.kept = t.rows.size();

  if (r.practice_excluded)
    r.notes.push_back(rows_text(r.practice_left_out) + " of practice trials left out (" +
                      (sel.practice == Practice::exclude ? "--exclude-practice" : "the default for a dtlab export") +
                      "; --include-practice keeps them)");
  else if (practice >= 0)
    r.notes.push_back("practice trials are included (" +
                      std::string(sel.practice == Practice::include ? "--include-practice" : "not a dtlab export") +
                      "; --exclude-practice leaves them out)");
  if (excluded >= 0)
    r.notes.push_back(sel.with_excluded
                          ? "rows marked in the excluded column are kept (--with-excluded)"
                          : rows_text(r.excluded_left_out) +
                                " of excluded participants or trials left out (non-empty excluded column; "
                                "--with-excluded keeps them)");
  if (!sel.where.empty())
    r.notes.push_back(rows_text(r.where_left_out) + " not matching --where left out");
  if (t.rows.empty() && r.read > 0)
    return Error{t.file, 0, 0, "", "no row is left after the row selection (" + rows_text(r.read) + " read, " +
                                       std::to_string(r.practice_left_out) + " practice, " +
                                       std::to_string(r.excluded_left_out) + " excluded, " +
                                       std::to_string(r.where_left_out) + " not matching --where)"};
  return r;
}

}  // namespace dtlab::stats
