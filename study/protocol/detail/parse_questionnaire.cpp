// Internal: the [questionnaire.<id>] tables. Each names an item type (`type`)
// or a standard instrument (`instrument`), optionally `when` it is asked;
// the type's or instrument's own keys are read as its registration declares
// them (study/questionnaire: KeySpec), so a new item type needs no change
// here. A key of another type is an error naming the types it belongs to;
// the type's check then holds the item against the design (names must
// exist). An instrument block becomes its published items in its place.
// Runs after the factors, scenarios and renderings. Never aborts: every
// problem is a Diagnostic at the key's line.
#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "study/protocol/detail/parser.h"

namespace dtlab::protocol::detail {

namespace {

namespace q = dtlab::questionnaire;

// The type's checks report here; keys become positions and field paths of the item's table.
class ItemProblems final : public q::Problems {
 public:
  ItemProblems(TableReader& r, Diagnostics& d) : r_(r), d_(d) {}
  void error(std::string_view key, const std::string& message) override {
    d_.error(key.empty() ? r_.pos() : r_.pos(key), key.empty() ? r_.path() : r_.field(key), message);
  }
  void error_at(std::string_view key, std::size_t index, const std::string& message) override {
    const toml::node* n = r_.node(key);
    const toml::array* a = n ? n->as_array() : nullptr;
    const toml::node* e = a && index < a->size() ? a->get(index) : nullptr;
    d_.error(e ? pos_of(*e) : r_.pos(key), indexed(r_.field(key), index), message);
  }
  void warning(std::string_view key, const std::string& message) override {
    d_.warning(key.empty() ? r_.pos() : r_.pos(key), key.empty() ? r_.path() : r_.field(key), message);
  }

 private:
  TableReader& r_;
  Diagnostics& d_;
};

// One declared key as its kind reads it; nullopt when absent (an error if required) or wrong.
std::optional<q::KeyValue> read_key(TableReader& r, const q::KeySpec& k, Diagnostics& d) {
  const limits::Ints ints{static_cast<std::int64_t>(k.min), static_cast<std::int64_t>(k.max)};
  const limits::Numbers numbers{k.min, k.max};
  switch (k.kind) {
    case q::KeyKind::text:
      if (auto v = r.string(k.name, k.required)) return *v;
      break;
    case q::KeyKind::choice:
      if (auto v = r.choice_of(k.name, k.required, k.allowed)) return *v;
      break;
    case q::KeyKind::boolean:
      if (auto v = r.boolean(k.name, k.required)) return *v;
      break;
    case q::KeyKind::integer:
      if (auto v = r.integer(k.name, k.required, ints)) return *v;
      break;
    case q::KeyKind::number:
      if (auto v = r.number(k.name, k.required, numbers)) return *v;
      break;
    case q::KeyKind::strings:
      if (auto v = r.strings(k.name, k.required, ints)) return *v;
      break;
    case q::KeyKind::int_range:
      if (auto v = r.int_range(k.name, k.required, ints, k.increasing))
        return q::NumberPair{static_cast<double>(v->min), static_cast<double>(v->max)};
      break;
    case q::KeyKind::number_range:
      if (auto v = r.number_range(k.name, k.required, numbers)) {
        if (k.increasing && !(v->min < v->max)) {
          d.error(r.pos(k.name), r.field(k.name), "expected [min, max] with min < max");
          break;
        }
        return q::NumberPair{v->min, v->max};
      }
      break;
  }
  return std::nullopt;
}

// Reads `specs` into keys (fallbacks where absent or wrong); records the keys the file sets.
void read_keys(TableReader& r, const std::vector<q::KeySpec>& specs, q::Keys& keys,
               std::set<std::string, std::less<>>& written, Diagnostics& d) {
  for (const q::KeySpec& k : specs) {
    if (r.has(k.name)) written.insert(k.name);
    auto v = read_key(r, k, d);
    keys[k.name] = v ? std::move(*v) : k.fallback;
  }
}

// Keys of other types (and instruments) the table sets: an error naming where they belong.
void foreign_keys(TableReader& r, const std::vector<q::KeySpec>& own, const std::string& what, Diagnostics& d) {
  std::map<std::string, std::vector<std::string>> owners;  // key -> "type = \"x\"", ...
  for (const q::ItemType* t : q::item_types())
    for (const q::KeySpec& k : t->keys) owners[k.name].push_back("type = \"" + t->name + "\"");
  for (const q::Instrument* i : q::instruments())
    for (const q::KeySpec& k : i->keys) owners[k.name].push_back("instrument = \"" + i->name + "\"");
  for (const auto& [key, where] : owners) {
    if (std::any_of(own.begin(), own.end(), [&](const q::KeySpec& k) { return k.name == key; })) continue;
    if (!r.has(key)) continue;
    std::string list;
    for (std::size_t i = 0; i < where.size(); ++i) list += (i ? " or " : "") + where[i];
    d.error(r.pos(key), r.field(key), "applies only to " + list + "; this item is " + what);
  }
}

std::vector<std::string> type_names() {
  std::vector<std::string> out;
  for (const q::ItemType* t : q::item_types()) out.push_back(t->name);
  return out;
}

std::vector<std::string> instrument_names() {
  std::vector<std::string> out;
  for (const q::Instrument* i : q::instruments()) out.push_back(i->name);
  return out;
}

// `when`: "end" (absent), "block", "task" or "level:<factor>" of a declared factor.
q::When read_when(TableReader& r, ParseState& s) {
  const auto text = r.string("when", false);
  if (!text) return {};
  const auto w = q::parse_when(*text);
  if (!w) {
    s.d.error(r.pos("when"), r.field("when"),
              "unknown value \"" + *text + "\"; expected \"end\", \"block\", \"task\" or \"level:<factor>\"");
    return {};
  }
  if (w->kind == q::When::Kind::level && !find_factor(s.p, w->factor)) {
    s.d.error(r.pos("when"), r.field("when"),
              "no factor named '" + w->factor + "' (factors: " + quoted_list(factor_names(s.p)) + ")");
    return {};
  }
  return *w;
}

void parse_item(const std::string& id, TableReader& r, const q::ItemType& type, const q::DesignNames& names,
                ParseState& s) {
  q::Item item;
  item.id = id;
  item.type = &type;
  item.when = read_when(r, s);
  if (auto v = r.string("prompt", true)) item.prompt = *v;
  const int errors_before = s.d.errors();
  read_keys(r, type.keys, item.keys, item.written, s.d);
  const bool keys_ok = s.d.errors() == errors_before;  // every key of the type read: its check may use them all
  foreign_keys(r, type.keys, "\"" + type.name + "\"", s.d);
  r.finish();
  ItemProblems problems(r, s.d);
  if (type.check && keys_ok) type.check(item, names, problems);
  s.p.questionnaire.push_back(std::move(item));
}

// An instrument item's wording in the participant's language: [questionnaire.<id>.wording.<sub>].
struct ItemWording {
  Pos at;
  std::string path;
  std::optional<std::string> prompt;
  std::optional<std::vector<std::string>> anchors, labels;
  bool used = false;
};

// The `wording` table of an instrument block, by sub-item id ("mental", "q3") or group ("w": every
// "w.*" item, e.g. the NASA-TLX's pairwise comparisons).
std::map<std::string, ItemWording, std::less<>> read_wording(TableReader& r, ParseState& s) {
  std::map<std::string, ItemWording, std::less<>> out;
  const toml::table* t = r.table("wording", false);
  if (!t) return out;
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string sub(k->str());
    ItemWording w{pos_of(*k), join(r.field("wording"), sub), {}, {}, {}, false};
    if (!n->is_table()) {
      s.d.error(pos_of(*n), w.path, "expected a table with prompt (and anchors or labels), got " + type_name(*n));
      continue;
    }
    TableReader wr(*n->as_table(), w.path, s.d, pos_of(*k));
    w.prompt = wr.string("prompt", false);
    w.anchors = wr.strings("anchors", false, {1, 100});
    w.labels = wr.strings("labels", false, {1, 100});
    wr.finish();
    out.emplace(sub, std::move(w));
  }
  return out;
}

// Replaces the published wording of `item` with the protocol's where it gives one. Anchors and
// labels must keep their number (they name the points of the item's scale).
void apply_wording(q::Item& item, std::map<std::string, ItemWording, std::less<>>& wording, ParseState& s) {
  auto it = wording.find(item.sub);
  if (it == wording.end() && item.sub.find('.') != std::string::npos)
    it = wording.find(std::string_view(item.sub).substr(0, item.sub.rfind('.')));
  if (it == wording.end()) return;
  ItemWording& w = it->second;
  w.used = true;
  if (w.prompt) item.prompt = *w.prompt;
  for (const auto& [key, given] : {std::pair{"anchors", &w.anchors}, std::pair{"labels", &w.labels}}) {
    if (!*given) continue;
    const auto published = item.keys.find(key);
    const auto* texts = published == item.keys.end() ? nullptr : std::get_if<std::vector<std::string>>(&published->second);
    if (!texts)
      s.d.error(w.at, join(w.path, key), "item " + item.sub + " has no " + key + " to reword");
    else if (texts->size() != (*given)->size())
      s.d.error(w.at, join(w.path, key), "expected " + std::to_string(texts->size()) + " " + key + " (as published), got " +
                                              std::to_string((*given)->size()));
    else
      published->second = **given;
  }
}

// A choice between sub-items (the NASA-TLX's pairwise comparisons) names them by the first line
// of their prompts, reworded or not, unless its own labels were reworded.
void label_choices_by_prompts(std::vector<q::Item>& items,
                              const std::map<std::string, ItemWording, std::less<>>& wording) {
  std::map<std::string, std::string> title;
  for (const q::Item& item : items) title[item.sub] = item.prompt.substr(0, item.prompt.find('\n'));
  for (q::Item& item : items) {
    const auto options = item.keys.find("options"), labels = item.keys.find("labels");
    if (options == item.keys.end() || labels == item.keys.end()) continue;
    const auto* subs = std::get_if<std::vector<std::string>>(&options->second);
    auto* shown = std::get_if<std::vector<std::string>>(&labels->second);
    const bool reworded = wording.count(item.sub) ||
                          (item.sub.find('.') != std::string::npos && wording.count(item.sub.substr(0, item.sub.rfind('.'))) &&
                           wording.find(item.sub.substr(0, item.sub.rfind('.')))->second.labels);
    if (!subs || !shown || reworded || subs->size() != shown->size()) continue;
    for (std::size_t i = 0; i < subs->size(); ++i)
      if (title.count((*subs)[i])) (*shown)[i] = title[(*subs)[i]];
  }
}

void parse_instrument(const std::string& id, TableReader& r, const q::Instrument& instrument, ParseState& s) {
  q::InstrumentUse use;
  use.id = id;
  use.instrument = &instrument;
  use.when = read_when(r, s);
  std::set<std::string, std::less<>> written;
  read_keys(r, instrument.keys, use.keys, written, s.d);
  auto wording = read_wording(r, s);
  foreign_keys(r, instrument.keys, "instrument = \"" + instrument.name + "\"", s.d);
  r.finish();
  std::vector<q::Item> items = q::instrument_items(use);
  for (q::Item& item : items) apply_wording(item, wording, s);
  label_choices_by_prompts(items, wording);
  for (const auto& [sub, w] : wording)
    if (!w.used) {
      std::string subs;
      for (const q::Item& item : items) subs += (subs.empty() ? "" : ", ") + item.sub;
      s.d.error(w.at, w.path, "\"" + sub + "\" is no item of " + instrument.name + " (its items: " + subs + ")");
    }
  for (q::Item& item : items) {
    use.items.push_back(item.id);
    s.p.questionnaire.push_back(std::move(item));
  }
  s.p.instruments.push_back(std::move(use));
}

}  // namespace

void parse_questionnaire(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("questionnaire", false);
  if (!t) return;
  const q::DesignNames names = design_names(s.p);
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string id(k->str());
    const std::string path = join("questionnaire", id);
    if (!is_identifier(id))
      s.d.error(pos_of(*k), path, "item id \"" + id + "\" is not an identifier (letters, digits, '_', '-')");
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with type and prompt, got " + type_name(*n));
      continue;
    }
    TableReader r(*n->as_table(), path, s.d, pos_of(*k));
    const bool has_type = r.has("type"), has_instrument = r.has("instrument");
    if (has_type && has_instrument)
      s.d.error(r.pos("instrument"), r.field("instrument"), "give either type or instrument, not both");
    if (!has_instrument || has_type) {
      const auto type = r.choice_of("type", true, type_names());
      if (const q::ItemType* found = type ? q::find_item_type(*type) : nullptr) {
        parse_item(id, r, *found, names, s);
        continue;
      }
    } else if (const auto name = r.choice_of("instrument", true, instrument_names())) {
      parse_instrument(id, r, *q::find_instrument(*name), s);
      continue;
    }
    // No usable type: its keys cannot be checked, so do not call them unknown.
    for (const q::ItemType* type : q::item_types())
      for (const q::KeySpec& key : type->keys) r.has(key.name);
    for (const q::Instrument* i : q::instruments())
      for (const q::KeySpec& key : i->keys) r.has(key.name);
    for (const char* key : {"prompt", "when", "instrument"}) r.has(key);
    r.finish();
  }
}

}  // namespace dtlab::protocol::detail
