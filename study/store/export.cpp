// CSV export of trial_table; see export.h. Numbers are written with
// std::to_chars (shortest form that reads back to the same double, never
// locale-dependent), so the file round-trips exactly through R and pandas.
#include "study/store/export.h"

#include <charconv>
#include <cstdio>

#include "study/store/detail/readonly.h"
#include "study/store/store.h"

namespace dtlab::store {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

namespace {

std::string number(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

Result<ExportSummary> export_trials_csv(const std::string& db_path, std::ostream& out) {
  auto opened = detail::open_readonly_dtlab(db_path);
  if (!opened) return opened.error();
  detail::Db& db = *opened;

  // One read transaction: the export is a consistent snapshot even while a
  // session keeps writing to the file.
  if (auto s = db.exec("BEGIN", "starting a read transaction"); !s) return s.error();
  const char* what = "reading trial_table";
  auto st = detail::Stmt::prepare(db, "SELECT * FROM trial_table ORDER BY enrollment_index, position", what);
  if (!st) return st.error();
  ExportSummary sum;
  for (int c = 0; c < st->columns(); ++c) sum.columns.push_back(st->column_name(c));
  std::string line;
  for (std::size_t c = 0; c < sum.columns.size(); ++c) line += (c ? "," : "") + csv_field(sum.columns[c]);
  out << line << '\n';
  for (;;) {
    auto row = st->step(what);
    if (!row) return row.error();
    if (!*row) break;
    line.clear();
    for (int c = 0; c < st->columns(); ++c) {
      if (c) line += ',';
      switch (st->column_type(c)) {
        case SQLITE_NULL: line += "NA"; break;
        case SQLITE_INTEGER: line += std::to_string(st->int64(c)); break;
        case SQLITE_FLOAT: line += number(st->real(c)); break;
        default: line += csv_field(st->text(c)); break;
      }
    }
    out << line << '\n';
    ++sum.rows;
  }
  db.exec("COMMIT", "ending the read transaction");
  if (!out) return Error{db_path, 0, 0, "", "writing the CSV failed"};
  return sum;
}

}  // namespace dtlab::store
