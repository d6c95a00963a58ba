// Internal: typed, position-aware reading of a parsed TOML document; see reader.h.
// Every message says what was found and what was expected. Nothing here throws
// on bad input.
#include "study/protocol/detail/reader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

#include "study/common/text.h"

namespace dtlab::protocol::detail {

namespace {

std::string num(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string interval(limits::Numbers r) { return "[" + num(r.min) + ", " + num(r.max) + "]"; }

bool inside(double v, limits::Numbers r) { return std::isfinite(v) && v >= r.min && v <= r.max; }

// Printable form of a string found in the file (quoted, control bytes escaped, shortened).
std::string shown(std::string_view s) {
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size() && i < 60; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (s.size() > 60) out += "...";
  return out + "\"";
}

}  // namespace

Pos pos_of(const toml::node& node) {
  const auto& b = node.source().begin;
  return {static_cast<int>(b.line), static_cast<int>(b.column)};
}

Pos pos_of(const toml::key& key) {
  const auto& b = key.source().begin;
  return {static_cast<int>(b.line), static_cast<int>(b.column)};
}

void Diagnostics::error(Pos at, std::string field, std::string message) {
  list_.push_back({Severity::error, Error{file_, at.line, at.column, std::move(field), std::move(message)}});
  ++errors_;
}

void Diagnostics::warning(Pos at, std::string field, std::string message) {
  list_.push_back({Severity::warning, Error{file_, at.line, at.column, std::move(field), std::move(message)}});
}

std::vector<Diagnostic> Diagnostics::take() {
  std::stable_sort(list_.begin(), list_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    if (a.where.line != b.where.line) return a.where.line < b.where.line;
    return a.where.column < b.where.column;
  });
  errors_ = 0;
  return std::move(list_);
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

std::string join(std::string_view path, std::string_view key) {
  if (path.empty()) return std::string(key);
  std::string s(path);
  s += '.';
  s += key;
  return s;
}

std::string indexed(std::string_view path, std::size_t i) {
  return std::string(path) + "[" + std::to_string(i) + "]";
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) s += ", ";
    s += "\"" + items[i] + "\"";
  }
  return s;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha(s[0])) return false;
  return std::all_of(s.begin(), s.end(), [&](char c) { return alpha(c) || digit(c) || c == '_' || c == '-'; });
}

std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(const toml::table& t) {
  std::vector<std::pair<const toml::key*, const toml::node*>> out;
  for (auto it = t.begin(); it != t.end(); ++it) out.emplace_back(&it->first, &it->second);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    const Pos pa = pos_of(*a.first), pb = pos_of(*b.first);
    if (pa.line != pb.line) return pa.line < pb.line;
    return pa.column < pb.column;
  });
  return out;
}

TableReader::TableReader(const toml::table& t, std::string path, Diagnostics& d, Pos where)
    : t_(t), path_(std::move(path)), d_(d), pos_(pos_of(t)) {
  if (pos_.line <= 0) pos_ = where;
}

Pos TableReader::pos(std::string_view key) const {
  if (const toml::node* n = t_.get(key)) {
    const Pos p = pos_of(*n);
    if (p.line > 0) return p;
  }
  return pos_;
}

const toml::node* TableReader::node(std::string_view key) {
  known_.emplace_back(key);
  return t_.get(key);
}

bool TableReader::has(std::string_view key) { return node(key) != nullptr; }

void TableReader::missing(std::string_view key, std::string_view expected) {
  d_.error(pos_, field(key), "missing required key '" + std::string(key) + "' (" + std::string(expected) + ")");
}

void TableReader::wrong_type(std::string_view key, const toml::node& n, std::string_view expected) {
  d_.error(pos_of(n), field(key), "expected " + std::string(expected) + ", got " + type_name(n));
}

std::optional<std::string> TableReader::string(std::string_view key, bool required, bool non_empty) {
  const toml::node* n = node(key);
  if (!n) {
    if (required) missing(key, "a string");
    return std::nullopt;
  }
  if (!n->is_string()) {
    wrong_type(key, *n, "a string");
    return std::nullopt;
  }
  std::string s = n->as_string()->get();
  if (non_empty && s.find_first_not_of(" \t\r\n") == std::string::npos) {
    d_.error(pos_of(*n), field(key), "expected a non-empty string");
    return std::nullopt;
  }
  return s;
}

std::optional<std::string> TableReader::choice(std::string_view key, bool required,
                                               std::initializer_list<std::string_view> allowed) {
  return choice_of(key, required, std::vector<std::string>(allowed.begin(), allowed.end()));
}

std::optional<std::string> TableReader::choice_of(std::string_view key, bool required,
                                                  const std::vector<std::string>& names) {
  const toml::node* n = node(key);
  if (!n) {
    if (required) missing(key, "one of " + quoted_list(names));
    return std::nullopt;
  }
  if (!n->is_string()) {
    wrong_type(key, *n, "a string, one of " + quoted_list(names));
    return std::nullopt;
  }
  const std::string& s = n->as_string()->get();
  if (std::find(names.begin(), names.end(), s) == names.end()) {
    d_.error(pos_of(*n), field(key), "unknown value " + shown(s) + "; expected one of " + quoted_list(names));
    return std::nullopt;
  }
  return s;
}

std::optional<std::int64_t> TableReader::integer(std::string_view key, bool required, limits::Ints range) {
  const auto [min, max] = range;
  const toml::node* n = node(key);
  const std::string expected = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!n) {
    if (required) missing(key, expected);
    return std::nullopt;
  }
  if (!n->is_integer()) {
    wrong_type(key, *n, expected);
    return std::nullopt;
  }
  const std::int64_t v = n->as_integer()->get();
  if (v < min || v > max) {
    d_.error(pos_of(*n), field(key), "value " + std::to_string(v) + " out of range; expected " + expected);
    return std::nullopt;
  }
  return v;
}

std::optional<bool> TableReader::boolean(std::string_view key, bool required) {
  const toml::node* n = node(key);
  if (!n) {
    if (required) missing(key, "true or false");
    return std::nullopt;
  }
  if (!n->is_boolean()) {
    wrong_type(key, *n, "true or false");
    return std::nullopt;
  }
  return n->as_boolean()->get();
}

namespace {
// A finite number from an integer or float node; nullopt if the node is neither.
std::optional<double> as_number(const toml::node& n) {
  if (n.is_integer()) return static_cast<double>(n.as_integer()->get());
  if (n.is_floating_point()) return n.as_floating_point()->get();
  return std::nullopt;
}
}  // namespace

std::optional<double> TableReader::number(std::string_view key, bool required, limits::Numbers range) {
  const toml::node* n = node(key);
  const std::string expected = "a number in " + interval(range);
  if (!n) {
    if (required) missing(key, expected);
    return std::nullopt;
  }
  const auto v = as_number(*n);
  if (!v) {
    wrong_type(key, *n, expected);
    return std::nullopt;
  }
  if (!inside(*v, range)) {
    d_.error(pos_of(*n), field(key), "value " + num(*v) + " out of range; expected " + expected);
    return std::nullopt;
  }
  return v;
}

std::optional<std::vector<std::string>> TableReader::texts(std::string_view key, std::size_t size,
                                                           const std::string& per) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const std::string expected = "an array of " + std::to_string(size) + " strings, one per " + per + " (\"\" = none)";
  const toml::array* a = n->as_array();
  if (!a) {
    wrong_type(key, *n, expected);
    return std::nullopt;
  }
  if (a->size() != size) {
    d_.error(pos_of(*n), field(key), "has " + std::to_string(a->size()) + " entries; expected " + expected);
    return std::nullopt;
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_string()) {
      d_.error(pos_of(e), indexed(field(key), i), "expected a string, got " + type_name(e));
      return std::nullopt;
    }
    out.push_back(e.as_string()->get());
  }
  return out;
}

std::optional<std::vector<std::string>> TableReader::strings(std::string_view key, bool required, limits::Ints count,
                                                             const std::vector<std::string>& allowed) {
  const auto min_count = static_cast<std::size_t>(count.min), max_count = static_cast<std::size_t>(count.max);
  const toml::node* n = node(key);
  std::string expected = "an array of " + std::to_string(min_count) + " to " + std::to_string(max_count) +
                         " unique strings";
  if (!allowed.empty()) expected += " from " + quoted_list(allowed);
  if (!n) {
    if (required) missing(key, expected);
    return std::nullopt;
  }
  const toml::array* a = n->as_array();
  if (!a) {
    wrong_type(key, *n, expected);
    return std::nullopt;
  }
  if (a->size() < min_count || a->size() > max_count) {
    d_.error(pos_of(*n), field(key),
             "has " + std::to_string(a->size()) + " entries; expected " + expected);
    return std::nullopt;
  }
  std::vector<std::string> out;
  bool ok = true;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string f = indexed(field(key), i);
    if (!e.is_string()) {
      d_.error(pos_of(e), f, "expected a string, got " + type_name(e));
      ok = false;
      continue;
    }
    const std::string& s = e.as_string()->get();
    if (allowed.empty() ? s.empty() : std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
      d_.error(pos_of(e), f,
               allowed.empty() ? "expected a non-empty string"
                               : "unknown value " + shown(s) + "; expected one of " + quoted_list(allowed));
      ok = false;
      continue;
    }
    const auto dup = std::find(out.begin(), out.end(), s);
    if (dup != out.end()) {
      d_.error(pos_of(e), f,
               "duplicate value " + shown(s) + " (already at index " + std::to_string(dup - out.begin()) + ")");
      ok = false;
      continue;
    }
    out.push_back(s);
  }
  if (!ok) return std::nullopt;
  return out;
}

std::optional<Range<double>> TableReader::number_range(std::string_view key, bool required, limits::Numbers range) {
  const toml::node* n = node(key);
  const std::string expected = "[min, max] with min <= max, each in " + interval(range);
  if (!n) {
    if (required) missing(key, expected);
    return std::nullopt;
  }
  const toml::array* a = n->as_array();
  if (!a || a->size() != 2) {
    d_.error(pos_of(*n), field(key),
             "expected " + expected + ", got " +
                 (a ? "an array of " + std::to_string(a->size()) + " values" : type_name(*n)));
    return std::nullopt;
  }
  double v[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const toml::node& e = *a->get(i);
    const auto x = as_number(e);
    if (!x) {
      d_.error(pos_of(e), indexed(field(key), i), "expected a number, got " + type_name(e));
      return std::nullopt;
    }
    if (!inside(*x, range)) {
      d_.error(pos_of(e), indexed(field(key), i), "value " + num(*x) + " out of range; expected " + expected);
      return std::nullopt;
    }
    v[i] = *x;
  }
  if (v[0] > v[1]) {
    d_.error(pos_of(*n), field(key), "min " + num(v[0]) + " > max " + num(v[1]) + "; expected " + expected);
    return std::nullopt;
  }
  return Range<double>{v[0], v[1]};
}

// Two integers at `key`, each in `range`; nullopt (after reporting) when absent or malformed.
std::optional<std::array<int, 2>> TableReader::two_ints(std::string_view key, bool required, limits::Ints range,
                                                         const std::string& expected) {
  const toml::node* n = node(key);
  if (!n) {
    if (required) missing(key, expected);
    return std::nullopt;
  }
  const toml::array* a = n->as_array();
  if (!a || a->size() != 2) {
    d_.error(pos_of(*n), field(key),
             "expected " + expected + ", got " +
                 (a ? "an array of " + std::to_string(a->size()) + " values" : type_name(*n)));
    return std::nullopt;
  }
  std::array<int, 2> v{};
  for (std::size_t i = 0; i < 2; ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_integer()) {
      d_.error(pos_of(e), indexed(field(key), i), "expected an integer, got " + type_name(e));
      return std::nullopt;
    }
    const std::int64_t x = e.as_integer()->get();
    if (x < range.min || x > range.max) {
      d_.error(pos_of(e), indexed(field(key), i),
               "value " + std::to_string(x) + " out of range; expected " + expected);
      return std::nullopt;
    }
    v[i] = static_cast<int>(x);
  }
  return v;
}

std::optional<Range<int>> TableReader::int_range(std::string_view key, bool required, limits::Ints range,
                                                 bool strictly_increasing) {
  const std::string expected = "[min, max] of integers with " + std::to_string(range.min) + " <= min " +
                               (strictly_increasing ? "<" : "<=") + " max <= " + std::to_string(range.max);
  const auto v = two_ints(key, required, range, expected);
  if (!v) return std::nullopt;
  if ((*v)[0] > (*v)[1] || (strictly_increasing && (*v)[0] == (*v)[1])) {
    d_.error(pos_of(*node(key)), field(key),
             "min " + std::to_string((*v)[0]) + ((*v)[0] == (*v)[1] ? " == max " : " > max ") +
                 std::to_string((*v)[1]) + "; expected " + expected);
    return std::nullopt;
  }
  return Range<int>{(*v)[0], (*v)[1]};
}

std::optional<std::pair<int, int>> TableReader::int_pair(std::string_view key, bool required, limits::Ints range) {
  const auto v = two_ints(key, required, range,
                          "two integers [a, b], each in [" + std::to_string(range.min) + ", " +
                              std::to_string(range.max) + "]");
  if (!v) return std::nullopt;
  return std::pair{(*v)[0], (*v)[1]};
}

const toml::table* TableReader::table(std::string_view key, bool required) {
  const toml::node* n = node(key);
  if (!n) {
    if (required) missing(key, "a table [" + field(key) + "]");
    return nullptr;
  }
  if (!n->is_table()) {
    wrong_type(key, *n, "a table [" + field(key) + "]");
    return nullptr;
  }
  return n->as_table();
}

void TableReader::finish() {
  std::vector<std::string> expected = known_;
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  for (const auto& [k, n] : in_file_order(t_)) {
    const std::string_view name = k->str();
    if (std::find(expected.begin(), expected.end(), name) != expected.end()) continue;
    std::string msg = "unknown key " + shown(name);
    const std::string best = nearest(name, expected);  // at most 2 edits away
    if (!best.empty()) msg += " (did you mean '" + best + "'?)";
    msg += expected.empty() ? "; this table takes no keys" : "; expected one of: ";
    for (std::size_t i = 0; i < expected.size(); ++i) msg += (i ? ", " : "") + expected[i];
    Pos at = pos_of(*k);
    if (at.line <= 0) at = pos_of(*n);
    d_.error(at, field(name), msg);
  }
}

}  // namespace dtlab::protocol::detail
