// The item-type seam's common half (questionnaire.h): the registry built from
// item_types.def, typed reads of an item's keys, `when`, the occasions of a
// plan, scopes, and the dispatch of expand / encode / simulate to the item's
// type (or instrument). Guarantees: the occasions of a plan depend on the plan
// and the items alone, so a resumed session finds the same ones.
#include "study/questionnaire/questionnaire.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {

// --- the registry -------------------------------------------------------------------------------------

std::span<const ItemType* const> item_types() {
  static const std::vector<const ItemType*> all = {
#define DTLAB_ITEM_TYPE(id) &item_type_##id(),
#include "study/questionnaire/item_types.def"
#undef DTLAB_ITEM_TYPE
  };
  return all;
}

const ItemType* find_item_type(std::string_view name) {
  for (const ItemType* t : item_types())
    if (t->name == name) return t;
  return nullptr;
}

std::string_view to_string(Measure m) {
  switch (m) {
    case Measure::ordinal: return "ordinal";
    case Measure::interval: return "interval";
    case Measure::nominal: return "nominal";
    case Measure::multiple: return "multiple";
    case Measure::text: return "text";
    case Measure::correct: return "correct";
  }
  return "?";
}

// --- keys ---------------------------------------------------------------------------------------------

const KeyValue& Item::value(std::string_view key) const {
  if (auto it = keys.find(key); it != keys.end()) return it->second;
  if (type)
    for (const KeySpec& k : type->keys)
      if (k.name == key) return k.fallback;
  throw std::invalid_argument("questionnaire item '" + id + "' has no key '" + std::string(key) + "'");
}

namespace {
template <class T>
const T& as(const Item& item, std::string_view key) {
  const T* v = std::get_if<T>(&item.value(key));
  if (!v) throw std::invalid_argument("questionnaire item '" + item.id + "': key '" + std::string(key) + "' is not set or of another kind");
  return *v;
}
}  // namespace

std::int64_t Item::integer(std::string_view key) const { return as<std::int64_t>(*this, key); }
double Item::number(std::string_view key) const { return as<double>(*this, key); }
bool Item::boolean(std::string_view key) const { return as<bool>(*this, key); }
const std::string& Item::text(std::string_view key) const {
  static const std::string none;
  if (std::holds_alternative<std::monostate>(value(key))) return none;
  return as<std::string>(*this, key);
}
const std::vector<std::string>& Item::strings(std::string_view key) const {
  static const std::vector<std::string> none;
  if (std::holds_alternative<std::monostate>(value(key))) return none;
  return as<std::vector<std::string>>(*this, key);
}
NumberPair Item::range(std::string_view key) const { return as<NumberPair>(*this, key); }

const DesignNames::Factor* DesignNames::factor(std::string_view name) const {
  for (const Factor& f : factors)
    if (f.name == name) return &f;
  return nullptr;
}

// --- when and occasions -----------------------------------------------------------------------------

std::string to_string(const When& w) {
  switch (w.kind) {
    case When::Kind::end: return "end";
    case When::Kind::block: return "block";
    case When::Kind::task: return "task";
    case When::Kind::level: return "level:" + w.factor;
  }
  return "?";
}

std::optional<When> parse_when(std::string_view text) {
  if (text == "end") return When{};
  if (text == "block") return When{When::Kind::block, ""};
  if (text == "task") return When{When::Kind::task, ""};
  if (text.rfind("level:", 0) == 0 && text.size() > 6) return When{When::Kind::level, std::string(text.substr(6))};
  return std::nullopt;
}

bool asked_at(const Item& item, const Occasion& o) {
  return item.when.kind == o.kind && (o.kind != When::Kind::level || item.when.factor == o.factor);
}

std::vector<Occasion> occasions(std::span<const Item> items, std::span<const PlanPoint> plan,
                                const std::vector<std::string>& factors) {
  const auto wanted = [&](When::Kind kind, const std::string& factor) {
    return std::any_of(items.begin(), items.end(),
                       [&](const Item& i) { return i.when.kind == kind && (kind != When::Kind::level || i.when.factor == factor); });
  };
  const bool tasks = wanted(When::Kind::task, ""), blocks = wanted(When::Kind::block, "");
  std::vector<std::string> level_factors;
  for (const std::string& f : factors)
    if (wanted(When::Kind::level, f)) level_factors.push_back(f);
  // The last plan index of each (factor, level).
  std::map<std::pair<std::string, std::string>, std::size_t> last;
  for (std::size_t i = 0; i < plan.size(); ++i)
    for (const auto& fl : plan[i].levels) last[fl] = i;

  std::vector<Occasion> out;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const PlanPoint& p = plan[i];
    const bool final = i + 1 == plan.size();
    const bool block_ends = final || plan[i + 1].block != p.block;
    const bool set_ends = block_ends || plan[i + 1].task != p.task;
    if (tasks && set_ends)
      out.push_back({When::Kind::task, "", "block=" + std::to_string(p.block) + ";task=" + p.task, p.block, p.task,
                     p.levels, p.position});
    if (blocks && block_ends)
      out.push_back({When::Kind::block, "", "block=" + std::to_string(p.block), p.block, "", p.levels, p.position});
    for (const std::string& f : level_factors)
      for (const auto& fl : p.levels)
        if (fl.first == f && last[fl] == i) out.push_back({When::Kind::level, f, f + "=" + fl.second, 0, "", {fl}, p.position});
    if (final && wanted(When::Kind::end, "")) out.push_back({When::Kind::end, "", "", 0, "", {}, p.position});
  }
  if (plan.empty() && wanted(When::Kind::end, "")) out.push_back(Occasion{});
  return out;
}

// --- questions ----------------------------------------------------------------------------------------

std::vector<Question> expand(const Item& item, const DesignNames& design) {
  if (item.type && item.type->expand) return item.type->expand(item, design);
  Question q;
  q.item = &item;
  return {q};
}

std::string stored_scope(const Occasion& o, const Question& q) {
  if (o.scope.empty()) return q.scope;
  if (q.scope.empty()) return o.scope;
  return o.scope + ";" + q.scope;
}

std::pair<std::string, std::string> split_scope(const Item& item, const std::string& stored) {
  const int parts = item.when.kind == When::Kind::end ? 0 : item.when.kind == When::Kind::task ? 2 : 1;
  std::size_t at = 0;
  for (int k = 0; k < parts; ++k) {
    const std::size_t semi = stored.find(';', at);
    if (semi == std::string::npos) return {stored, ""};
    at = semi + 1;
  }
  if (parts == 0) return {"", stored};
  return {stored.substr(0, at - 1), stored.substr(at)};
}

std::string field_of(const Question& q) {
  return "questionnaire." + (q.item ? q.item->id : std::string("?")) + (q.scope.empty() ? "" : "[" + q.scope + "]");
}

Result<StoredValue> encode(const Question& q, const Answer& a, const EncodeContext& ctx) {
  if (!q.item || !q.item->type || !q.item->type->encode)
    return Error{"", 0, 0, field_of(q), "the item has no type that stores answers", ErrorKind::internal};
  return q.item->type->encode(q, a, ctx);
}

Answer simulate(const Question& q, Experience& e) {
  const Item& item = *q.item;
  if (item.instrument && item.instrument->simulate) return item.instrument->simulate(item, q, e);
  return item.type->simulate(q, e);
}

std::string value_label(const Item& item, const StoredValue& v) {
  return item.type && item.type->label ? item.type->label(item, v) : "";
}

}  // namespace dtlab::questionnaire
