// The registry's command-line options (see technique_options.h).
#include "app/technique_options.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <sstream>

#include "app/commands.h"

namespace dtlab::app {

namespace {

using technique::KeySpec;

struct Given {
  std::string_view key;   // the protocol key
  std::string option;     // "--vdt-falloff"
  const std::string* value;
};

// The options given, as a KeyReader: a key's group reads them as it reads a protocol table.
class OptionKeys final : public technique::KeyReader {
 public:
  explicit OptionKeys(std::vector<Given> given) : given_(std::move(given)) {}
  std::optional<double> number(const KeySpec& k, bool) override {
    const Given* g = find(k.name);
    if (g == nullptr) return std::nullopt;
    double v = 0;
    try {
      std::size_t used = 0;
      v = std::stod(*g->value, &used);
      if (used != g->value->size() || !std::isfinite(v)) throw std::invalid_argument(*g->value);
    } catch (const std::exception&) {
      fail("render", kExitUsage, g->option + ": expected a number, got '" + *g->value + "'");
    }
    if (!(v >= k.min && v <= k.max)) out_of_range(*g, k);
    return v;
  }
  std::optional<std::int64_t> integer(const KeySpec& k, bool) override {
    const Given* g = find(k.name);
    if (g == nullptr) return std::nullopt;
    std::int64_t v = 0;
    try {
      std::size_t used = 0;
      v = std::stoll(*g->value, &used);
      if (used != g->value->size()) throw std::invalid_argument(*g->value);
    } catch (const std::exception&) {
      fail("render", kExitUsage, g->option + ": expected an integer, got '" + *g->value + "'");
    }
    if (!(static_cast<double>(v) >= k.min && static_cast<double>(v) <= k.max)) out_of_range(*g, k);
    return v;
  }
  std::optional<std::string> choice(const KeySpec& k, bool) override {
    const Given* g = find(k.name);
    if (g == nullptr) return std::nullopt;
    for (std::string_view c : k.choices)
      if (c == *g->value) return *g->value;
    fail("render", kExitUsage, g->option + ": expected " + choices(k) + ", got '" + *g->value + "'");
  }
  std::optional<bool> boolean(const KeySpec& k) override {
    const Given* g = find(k.name);
    if (g == nullptr) return std::nullopt;
    if (*g->value == "true") return true;
    if (*g->value == "false") return false;
    fail("render", kExitUsage, g->option + ": expected true or false, got '" + *g->value + "'");
  }
  bool has(std::string_view key) override { return find(key) != nullptr; }
  void error(std::string_view key, std::string message) override {
    const Given* g = find(key);
    fail("render", kExitUsage, (g ? g->option : std::string(key)) + ": " + message);
  }
  void warning(std::string_view key, std::string message) override {
    const Given* g = find(key);
    std::cerr << "dtlab render: warning: " << (g ? g->option : std::string(key)) << ": " << message << "\n";
  }
  static std::string choices(const KeySpec& k) {
    std::string list;
    for (std::string_view c : k.choices) list += (list.empty() ? "" : " | ") + std::string(c);
    return list;
  }

 private:
  const Given* find(std::string_view key) const {
    for (const Given& g : given_)
      if (g.key == key) return &g;
    return nullptr;
  }
  [[noreturn]] static void out_of_range(const Given& g, const KeySpec& k) {
    std::ostringstream m;
    m << g.option << ": must be " << k.min << ".." << k.max << ", got " << *g.value;
    fail("render", kExitUsage, m.str());
  }
  std::vector<Given> given_;
};

// "KIND: help (a..b)" as the option's help text.
std::string help_of(const KeySpec& k) {
  std::ostringstream h;
  h << k.help;
  if (k.kind == KeySpec::Kind::choice) h << ": " << OptionKeys::choices(k);
  if (k.kind == KeySpec::Kind::number || k.kind == KeySpec::Kind::integer) h << ", " << k.min << ".." << k.max;
  if (k.kind == KeySpec::Kind::boolean) h << ": true | false";
  h << " (protocol key " << k.name << ")";
  return h.str();
}

}  // namespace

void TechniqueOptions::add_to(CLI::App& cmd) {
  for (const technique::KeyGroup* g : technique::key_groups())
    for (const KeySpec& k : g->keys) {
      if (k.cli.empty()) continue;
      Entry& e = entries_.emplace_back(Entry{g, &k, nullptr, {}});
      e.option = cmd.add_option(std::string(k.cli), e.value, help_of(k));
    }
}

bool TechniqueOptions::has_options(const technique::KeyGroup& g) const {
  for (const Entry& e : entries_)
    if (e.group == &g) return true;
  return false;
}

std::string TechniqueOptions::given() const {
  std::string names;
  for (const Entry& e : entries_)
    if (e.option->count() > 0) names += (names.empty() ? "" : ", ") + e.option->get_name();
  return names;
}

std::string TechniqueOptions::misplaced(const technique::Technique& method) const {
  std::string names, readers;
  for (const Entry& e : entries_) {
    if (e.option->count() == 0 || method.reads(e.group->id)) continue;
    names += (names.empty() ? "" : ", ") + e.option->get_name();
    if (!readers.empty()) continue;
    for (const technique::Technique* t : technique::all())
      if (t->reads(e.group->id)) readers += (readers.empty() ? "--method " : " or ") + std::string(t->name);
  }
  return names.empty() ? "" : names + " apply to " + readers + " only";
}

void TechniqueOptions::apply(const technique::Technique& method, int width, int height,
                             technique::MethodSettings& out) const {
  technique::Keys keys;
  for (const technique::KeyGroup* g : technique::key_groups()) {
    if (!method.reads(g->id) || !has_options(*g)) continue;
    std::vector<Given> given;
    for (const Entry& e : entries_)
      if (e.group == g && e.option->count() > 0) given.push_back({e.key->name, e.option->get_name(), &e.value});
    OptionKeys reader(std::move(given));
    g->parse(reader, method, keys);
    if (g->to_frame == nullptr) continue;
    if (const auto problem = g->to_frame(method, keys, width, height, out)) {
      std::string option = problem->key;
      for (const Entry& e : entries_)
        if (e.group == g && e.key->name == problem->key) option = e.option->get_name();
      fail("render", kExitUsage, option + ": " + problem->message);
    }
  }
}

}  // namespace dtlab::app
