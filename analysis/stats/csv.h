// CSV input for the statistics: RFC 4180 text (comma separated, optional
// double quotes with "" as an escaped quote, LF or CRLF line ends, optional
// UTF-8 byte-order mark) read into a table of strings whose every row keeps
// the 1-based line it started on, so errors can name file, line and column.
// Guarantees: cells are returned verbatim (no number conversion, no trimming
// inside quotes); a row with the wrong number of fields is an Error, never
// silently padded. Never throws for bad input; never touches the file.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "study/common/error.h"

namespace dtlab::stats {

struct CsvTable {
  std::string file;                            // name used in error messages
  std::vector<std::string> header;             // column names, surrounding blanks trimmed; "" = unnamed
  std::vector<std::vector<std::string>> rows;  // data rows, header.size() cells each
  std::vector<int> line;                       // line[i]: 1-based line where rows[i] starts

  // Index of the column named `name`, or -1.
  int column(std::string_view name) const;
};

// Parses CSV text; `file` is only used in error messages. Blank lines are skipped.
Result<CsvTable> parse_csv(std::string_view text, std::string file);

// Reads and parses a CSV file; a missing or unreadable file is an Error.
Result<CsvTable> read_csv_file(const std::string& path);

// User text as error messages and warnings quote it: in single quotes, control
// bytes written as \xNN, and cut after `max_bytes` bytes with the full length
// named ("'aaaa...' (10485760 bytes)"), so a 10 MB field never floods stderr.
std::string quote_text(std::string_view text, std::size_t max_bytes = 60);

// A column, subject or level name for a message: as is when it is short and
// printable, else quote_text().
std::string name_for_message(std::string_view name);

}  // namespace dtlab::stats
