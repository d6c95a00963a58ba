// Loading and validating protocol files: reads the bytes (at most 1 MiB),
// refuses empty and binary files, parses TOML with toml++ and hands the
// document to detail/parse_*.cpp. Every failure, including a TOML syntax
// error, becomes a Diagnostic with file:line:column and the field at fault;
// nothing here throws to the caller or aborts.
#include "study/protocol/protocol.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "study/common/hash.h"
#include "study/protocol/detail/parser.h"

namespace dtlab::protocol {

namespace {

constexpr std::size_t kMaxProtocolBytes = 1 << 20;

struct Outcome {
  Protocol protocol;
  std::vector<Diagnostic> diagnostics;
};

// Best guess at the field a TOML syntax error is in: the last [table] header
// at or before the error line, plus the key written on the error line.
// A plain scan, no regex: the text may be arbitrary bytes.
std::string field_near(std::string_view text, int line) {
  const auto is_key_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  };
  std::string table, field;
  int current = 1;
  std::size_t start = 0;
  while (start <= text.size() && current <= line) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(start, end - start);
    const std::size_t b = l.find_first_not_of(" \t");
    if (b != std::string_view::npos) {
      l.remove_prefix(b);
      if (l.front() == '[') {  // [table] or [[array.of.tables]]
        std::size_t i = l.find_first_not_of("[ \t");
        std::size_t j = i;
        while (j < l.size() && is_key_char(l[j])) ++j;
        if (i != std::string_view::npos && j > i) table = std::string(l.substr(i, j - i));
      } else if (current == line) {  // key = value
        std::size_t j = 0;
        while (j < l.size() && is_key_char(l[j])) ++j;
        const std::size_t eq = l.find_first_not_of(" \t", j);
        if (j > 0 && eq != std::string_view::npos && l[eq] == '=') field = std::string(l.substr(0, j));
      }
    }
    start = end + 1;
    ++current;
  }
  if (field.empty()) return table;
  return table.empty() ? field : table + "." + field;
}

Outcome parse_text(std::string_view text, const std::string& path) {
  Outcome out;
  detail::Diagnostics d(path);
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    d.error({1, 1}, "",
            "the file is empty; a protocol declares at least id, title, participants, master_seed, "
            "[factors.*], [order], [scenarios.*] and [rendering.*] (docs/protocol.md)");
    out.diagnostics = d.take();
    return out;
  }
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const std::string_view before = text.substr(0, nul);
    const int line = 1 + static_cast<int>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t bol = before.rfind('\n');
    const int column = static_cast<int>(nul - (bol == std::string_view::npos ? 0 : bol + 1)) + 1;
    d.error({line, column}, "", "binary data (a NUL byte); a protocol is a UTF-8 TOML text file");
    out.diagnostics = d.take();
    return out;
  }
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const int line = static_cast<int>(e.source().begin.line);
    const int column = static_cast<int>(e.source().begin.column);
    d.error({line, column}, field_near(text, line), "TOML syntax error: " + std::string(e.description()));
    out.diagnostics = d.take();
    return out;
  } catch (const std::exception& e) {
    d.error({0, 0}, "", std::string("cannot parse the file: ") + e.what());
    out.diagnostics = d.take();
    return out;
  }
  detail::ParseState s{d, out.protocol};
  detail::parse_document(root, s);
  out.diagnostics = d.take();
  return out;
}

// The file's bytes, or an error diagnostic.
std::optional<std::string> read_file(const std::string& path, std::vector<Diagnostic>& diags) {
  const auto fail = [&](std::string message) {
    diags.push_back({Severity::error, Error{path, 0, 0, "", std::move(message)}});
    return std::nullopt;
  };
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) return fail("cannot read the protocol: no such file");
  if (std::filesystem::is_directory(st)) return fail("cannot read the protocol: it is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(std::string("cannot read the protocol: ") + std::strerror(errno));
  std::string bytes;
  bytes.resize(kMaxProtocolBytes + 1);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (in.bad()) return fail(std::string("cannot read the protocol: ") + std::strerror(errno));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (bytes.size() > kMaxProtocolBytes)
    return fail("the file is larger than 1 MiB; a protocol is a small TOML text file");
  return bytes;
}

Result<Protocol> to_result(Outcome out, std::string_view text, const std::string& path) {
  for (const auto& d : out.diagnostics)
    if (d.severity == Severity::error) return d.where;
  Protocol p = std::move(out.protocol);
  p.source_path = path;
  p.source_text = std::string(text);
  p.sha256 = sha256_hex(text);
  return p;
}

}  // namespace

Result<Protocol> load_protocol(const std::string& path) {
  std::vector<Diagnostic> diags;
  const auto text = read_file(path, diags);
  if (!text) return diags.front().where;
  return to_result(parse_text(*text, path), *text, path);
}

Result<Protocol> load_protocol_text(std::string_view text, const std::string& source_path) {
  return to_result(parse_text(text, source_path), text, source_path);
}

std::vector<Diagnostic> validate_protocol_file(const std::string& path) {
  std::vector<Diagnostic> diags;
  const auto text = read_file(path, diags);
  if (!text) return diags;
  return parse_text(*text, path).diagnostics;
}

std::vector<Diagnostic> validate_protocol_text(std::string_view text, const std::string& source_path) {
  return parse_text(text, source_path).diagnostics;
}

bool has_errors(const std::vector<Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics)
    if (d.severity == Severity::error) return true;
  return false;
}

namespace {

// "a.b[2].c" -> {"a", "b", "[2]", "c"}: keys and array indices in order.
std::vector<std::string> path_parts(std::string_view field) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : field) {
    if (c == '.' || c == '[') {
      if (!cur.empty()) parts.push_back(cur);
      cur = c == '[' ? "[" : "";
    } else if (c == ']') {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) parts.push_back(cur);
  return parts;
}

SourcePos position_of(const toml::node& n) {
  const auto& b = n.source().begin;
  return {static_cast<int>(b.line), static_cast<int>(b.column)};
}

// The deepest node along `parts` that has a source position (the root table counts as line 1).
SourcePos walk(const toml::table& root, const std::vector<std::string>& parts, bool* complete) {
  SourcePos at{1, 1};
  const toml::node* n = &root;
  *complete = false;
  for (const std::string& part : parts) {
    const toml::node* next = nullptr;
    if (part.front() == '[') {
      const toml::array* a = n->as_array();
      char* end = nullptr;
      const unsigned long i = std::strtoul(part.c_str() + 1, &end, 10);
      if (a && end && *end == '\0' && i < a->size()) next = a->get(i);
    } else if (const toml::table* t = n->as_table()) {
      next = t->get(part);
    }
    if (!next) return at;
    n = next;
    if (const SourcePos p = position_of(*n); p.line > 0) at = p;
  }
  *complete = true;
  return at;
}

}  // namespace

SourcePos field_position(const Protocol& p, std::string_view field) {
  if (p.source_text.empty()) return {};
  toml::table root;
  try {
    root = toml::parse(p.source_text, p.source_path);
  } catch (const std::exception&) {
    return {};
  }
  std::vector<std::string> parts = path_parts(field);
  bool complete = false;
  const SourcePos exact = walk(root, parts, &complete);
  if (complete) return exact;
  // scenarios.<s>.tasks.<t>.<key>: a scene key the task does not set comes from the scenario.
  if (parts.size() >= 5 && parts[0] == "scenarios" && parts[2] == "tasks") {
    std::vector<std::string> inherited{parts[0], parts[1]};
    inherited.insert(inherited.end(), parts.begin() + 4, parts.end());
    const SourcePos from_scenario = walk(root, inherited, &complete);
    if (complete) return from_scenario;
  }
  return exact;
}

Error error_at(const Protocol& p, std::string field, std::string message) {
  const SourcePos at = field_position(p, field);
  return Error{p.source_path, at.line, at.column, std::move(field), std::move(message)};
}

std::string_view to_string(FactorRole role) {
  switch (role) {
    case FactorRole::scenario: return "scenario";
    case FactorRole::rendering: return "rendering";
    case FactorRole::none: break;
  }
  return "none";
}

std::string_view to_string(Scheme scheme) {
  switch (scheme) {
    case Scheme::latin_square: return "latin-square";
    case Scheme::williams: return "williams";
    case Scheme::full_permutation: return "full-permutation";
    case Scheme::random: return "random";
    case Scheme::fixed: break;
  }
  return "fixed";
}

std::string_view to_string(OrderUnit unit) { return unit == OrderUnit::blocks ? "blocks" : "conditions"; }

std::string_view to_string(ScenarioKind kind) {
  return kind == ScenarioKind::walkthrough ? "walkthrough" : "abstract";
}

std::string_view to_string(TaskType type) {
  switch (type) {
    case TaskType::identify_letter: return "identify-letter";
    case TaskType::find_unique: return "find-unique";
    case TaskType::count_kind: return "count-kind";
    case TaskType::count_targets: break;
  }
  return "count-targets";
}

namespace {
template <class T>
const T* by_name(const std::vector<T>& items, std::string_view name) {
  for (const T& item : items)
    if (item.name == name) return &item;
  return nullptr;
}
}  // namespace

const Factor* find_factor(const Protocol& p, std::string_view name) { return by_name(p.factors, name); }

const std::string& level_label(const Factor& f, int level) {
  const auto i = static_cast<std::size_t>(level);
  return i < f.labels.size() && !f.labels[i].empty() ? f.labels[i] : f.levels.at(i);
}
const Scenario* find_scenario(const Protocol& p, std::string_view name) { return by_name(p.scenarios, name); }
const Rendering* find_rendering(const Protocol& p, std::string_view name) { return by_name(p.renderings, name); }

const Task* find_task(const Scenario& s, std::string_view id) {
  for (const Task& t : s.tasks)
    if (t.id == id) return &t;
  return nullptr;
}

const Factor* factor_with_role(const Protocol& p, FactorRole role) {
  for (const Factor& f : p.factors)
    if (f.role == role) return &f;
  return nullptr;
}

questionnaire::DesignNames design_names(const Protocol& p) {
  questionnaire::DesignNames n;
  for (const Factor& f : p.factors) n.factors.push_back({f.name, f.levels});
  for (const Scenario& sc : p.scenarios) n.scenarios.push_back(sc.name);
  for (const Rendering& r : p.renderings) n.renderings.push_back(r.name);
  if (const Factor* f = factor_with_role(p, FactorRole::rendering)) n.rendering_factor = f->name;
  return n;
}

}  // namespace dtlab::protocol
