// Internal: typed, position-aware reading of a parsed TOML document.
// Every getter reports what is wrong as a Diagnostic (file:line:column, dotted
// field path, what was expected) and returns nullopt instead of throwing.
// TableReader remembers which keys were asked for, so finish() can report
// every other key of the table as unknown. Never aborts on any input.
#pragma once
#include <array>
#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/limits.h"
#include "study/protocol/protocol.h"

namespace dtlab::protocol::detail {

struct Pos {
  int line = 0;
  int column = 0;
};
Pos pos_of(const toml::node& node);  // where the value starts
Pos pos_of(const toml::key& key);    // where the key is written

// Collects diagnostics for one file.
class Diagnostics {
 public:
  explicit Diagnostics(std::string file) : file_(std::move(file)) {}
  void error(Pos at, std::string field, std::string message);
  void warning(Pos at, std::string field, std::string message);
  bool has_errors() const { return errors_ > 0; }
  int errors() const { return errors_; }
  std::vector<Diagnostic> take();  // all of them, sorted by line then column (stable)

 private:
  std::string file_;
  std::vector<Diagnostic> list_;
  int errors_ = 0;
};

std::string type_name(const toml::node& node);  // "a string", "an integer", ...
std::string join(std::string_view path, std::string_view key);  // "a.b" (or "b" for the root)
std::string indexed(std::string_view path, std::size_t i);      // "a[2]"
std::string quoted_list(const std::vector<std::string>& items);  // "\"a\", \"b\""
bool is_identifier(std::string_view s);  // [A-Za-z][A-Za-z0-9_-]*, at most 64 characters

// The entries of a table in the order they are written in the file
// (toml++ keeps tables sorted by key; file order matters for factors, tasks...).
std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(const toml::table& t);

class TableReader {
 public:
  // `path` is the dotted field path of the table ("" for the document root);
  // `where` is used for missing keys when the table itself has no position.
  TableReader(const toml::table& t, std::string path, Diagnostics& d, Pos where = {1, 1});

  const std::string& path() const { return path_; }
  std::string field(std::string_view key) const { return join(path_, key); }
  Pos pos() const { return pos_; }                 // the table's own position
  Pos pos(std::string_view key) const;             // the key's value, or pos()
  const toml::node* node(std::string_view key);    // marks the key known; nullptr if absent
  bool has(std::string_view key);                  // marks the key known

  // Typed getters: nullopt when absent (an error if `required`) or wrong.
  std::optional<std::string> string(std::string_view key, bool required, bool non_empty = true);
  std::optional<std::string> choice(std::string_view key, bool required,
                                    std::initializer_list<std::string_view> allowed);
  std::optional<std::string> choice_of(std::string_view key, bool required, const std::vector<std::string>& allowed);
  std::optional<std::int64_t> integer(std::string_view key, bool required, limits::Ints range);
  std::optional<double> number(std::string_view key, bool required, limits::Numbers range);
  std::optional<bool> boolean(std::string_view key, bool required);  // true or false
  // Array of unique strings, as many as `count` allows, each passing `allowed` (empty = anything non-empty).
  std::optional<std::vector<std::string>> strings(std::string_view key, bool required, limits::Ints count,
                                                  const std::vector<std::string>& allowed = {});
  // Array of exactly `size` strings, each any text ("" too), duplicates allowed: wording given
  // per entry of another array (a factor's level labels and instructions).
  std::optional<std::vector<std::string>> texts(std::string_view key, std::size_t size, const std::string& per);
  // [min, max]: two numbers, each in `range`, min <= max.
  std::optional<Range<double>> number_range(std::string_view key, bool required, limits::Numbers range);
  // [min, max]: two integers, each in `range`, min <= max (min < max if strictly_increasing).
  std::optional<Range<int>> int_range(std::string_view key, bool required, limits::Ints range,
                                      bool strictly_increasing = false);
  // Two integers [a, b], each in `range` (no order between them).
  std::optional<std::pair<int, int>> int_pair(std::string_view key, bool required, limits::Ints range);
  const toml::table* table(std::string_view key, bool required);

  // Reports every key of the table no getter asked for. Call once, at the end.
  void finish();

 private:
  void missing(std::string_view key, std::string_view expected);
  std::optional<std::array<int, 2>> two_ints(std::string_view key, bool required, limits::Ints range,
                                             const std::string& expected);
  void wrong_type(std::string_view key, const toml::node& n, std::string_view expected);

  const toml::table& t_;
  std::string path_;
  Diagnostics& d_;
  Pos pos_;
  std::vector<std::string> known_;
};

}  // namespace dtlab::protocol::detail
