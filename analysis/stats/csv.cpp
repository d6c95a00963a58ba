// RFC 4180 reader; see csv.h. A small state machine over the bytes: no
// dependency offers a CSV reader among the project's Debian packages, and the
// grammar is four rules (field, quoted field, separator, record end).
#include "analysis/stats/csv.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace dtlab::stats {
namespace {

std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(b, e - b));
}

bool all_blank(const std::vector<std::string>& record) {
  for (const auto& f : record)
    if (!trim(f).empty()) return false;
  return true;
}

}  // namespace

int CsvTable::column(std::string_view name) const {
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

Result<CsvTable> parse_csv(std::string_view text, std::string file) {
  CsvTable t;
  t.file = std::move(file);
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);

  std::vector<std::vector<std::string>> records;
  std::vector<int> starts;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false;      // inside a quoted field
  bool was_quoted = false;  // current field began with a quote
  int line = 1, record_line = 1;

  auto end_field = [&] {
    record.push_back(was_quoted ? field : trim(field));
    field.clear();
    was_quoted = false;
  };
  auto end_record = [&] {
    end_field();
    if (!all_blank(record) || record.size() > 1) {
      records.push_back(std::move(record));
      starts.push_back(record_line);
    }
    record.clear();
  };

  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0')
      return Error{t.file, line, static_cast<int>(record.size() + 1), "",
                   "NUL byte (\\0) in field " + std::to_string(record.size() + 1) +
                       ": the file is binary or corrupt, not CSV text"};
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field.push_back('"');
          ++i;
        } else {
          quoted = false;
        }
      } else {
        if (c == '\n') ++line;
        field.push_back(c);
      }
      continue;
    }
    if (c == '"') {
      if (!trim(field).empty())
        return Error{t.file, line, static_cast<int>(record.size() + 1), "",
                     "a quote may only open a field (write \"\" inside a quoted field)"};
      field.clear();
      quoted = true;
      was_quoted = true;
    } else if (c == ',') {
      end_field();
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      end_record();
      ++line;
      record_line = line;
    } else {
      if (was_quoted && c != ' ' && c != '\t')
        return Error{t.file, line, static_cast<int>(record.size() + 1), "",
                     "text after the closing quote of a field"};
      if (!was_quoted) field.push_back(c);
    }
  }
  if (quoted) return Error{t.file, record_line, 0, "", "a quoted field is never closed"};
  if (!field.empty() || !record.empty()) end_record();

  if (records.empty()) return Error{t.file, 0, 0, "", "the file is empty: expected a header line of column names"};
  t.header = std::move(records.front());
  for (size_t c = 0; c < t.header.size(); ++c) {
    if (t.header[c].empty()) continue;  // an unnamed column (e.g. a pandas index) cannot be selected
    for (size_t d = 0; d < c; ++d)
      if (t.header[d] == t.header[c])
        return Error{t.file, starts.front(), static_cast<int>(c + 1), name_for_message(t.header[c]),
                     "column name appears twice in the header"};
  }
  for (size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() != t.header.size())
      return Error{t.file, starts[r], 0, "",
                   "expected " + std::to_string(t.header.size()) + " fields as in the header, found " +
                       std::to_string(records[r].size())};
    t.rows.push_back(std::move(records[r]));
    t.line.push_back(starts[r]);
  }
  return t;
}

std::string quote_text(std::string_view text, std::size_t max_bytes) {
  std::string s = "'";
  const std::size_t shown = std::min(text.size(), max_bytes);
  for (std::size_t i = 0; i < shown; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7F) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", c);
      s += b;
    } else {
      s += static_cast<char>(c);
    }
  }
  s += shown < text.size() ? "...'" : "'";
  if (shown < text.size()) s += " (" + std::to_string(text.size()) + " bytes)";
  return s;
}

std::string name_for_message(std::string_view name) {
  constexpr std::size_t kShort = 60;
  bool printable = name.size() <= kShort;
  for (char ch : name) printable = printable && static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7F;
  return printable ? std::string(name) : quote_text(name, kShort);
}

Result<CsvTable> read_csv_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, 0, "", "cannot open the file for reading"};
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return Error{path, 0, 0, "", "read error"};
  return parse_csv(ss.str(), path);
}

}  // namespace dtlab::stats
