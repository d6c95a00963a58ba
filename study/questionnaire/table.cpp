// answer_table (table.h): stored answers with their occasions' conditions,
// and the instruments' scores per participant and occasion.
#include "study/questionnaire/table.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace dtlab::questionnaire {

std::vector<std::optional<double>> score_occasion(const InstrumentUse& use, const SubAnswers& answers) {
  if (!use.instrument || !use.instrument->score) return {};
  return use.instrument->score(use.keys, answers);
}

namespace {

// Sort key of a row: occasion order, item order, then its own scope.
using Key = std::tuple<std::size_t, double, std::string>;

// The occasion of `item` stored under `occasion_scope` for a participant with `plan`: the one the
// plan has, else what the scope says (a block number, a level).
Occasion occasion_of(const Item& item, const std::string& occasion_scope, const std::vector<Occasion>& known,
                     const std::vector<PlanPoint>& plan, std::size_t& order) {
  for (std::size_t i = 0; i < known.size(); ++i)
    if (known[i].kind == item.when.kind && known[i].factor == item.when.factor && known[i].scope == occasion_scope) {
      order = i;
      return known[i];
    }
  order = known.size();
  Occasion o;
  o.kind = item.when.kind;
  o.factor = item.when.factor;
  o.scope = occasion_scope;
  if (o.kind == When::Kind::block || o.kind == When::Kind::task) {
    if (occasion_scope.rfind("block=", 0) == 0) o.block = std::atoi(occasion_scope.c_str() + 6);
    if (const auto t = occasion_scope.find(";task="); t != std::string::npos) o.task = occasion_scope.substr(t + 6);
    for (const PlanPoint& p : plan)
      if (p.block == o.block) o.levels = p.levels;
  } else if (o.kind == When::Kind::level) {
    const auto eq = occasion_scope.find('=');
    if (eq != std::string::npos) o.levels = {{occasion_scope.substr(0, eq), occasion_scope.substr(eq + 1)}};
  }
  return o;
}

TableRow row_at(const std::string& participant, const Occasion& o, const std::vector<std::string>& factors) {
  TableRow r;
  r.participant = participant;
  r.occasion = to_string(When{o.kind, o.factor});
  r.occasion_scope = o.scope;
  r.block = o.block;
  r.task = o.task;
  r.levels.assign(factors.size(), "");
  for (const auto& [factor, level] : o.levels) {
    const auto it = std::find(factors.begin(), factors.end(), factor);
    if (it != factors.end()) r.levels[static_cast<std::size_t>(it - factors.begin())] = level;
  }
  return r;
}

}  // namespace

Table answer_table(std::span<const Item> items, std::span<const InstrumentUse> instruments,
                   const std::vector<std::string>& factors, std::span<const ParticipantPlan> plans,
                   std::span<const StoredAnswer> answers) {
  Table t;
  t.factors = factors;
  std::map<std::string, std::size_t, std::less<>> item_index;
  for (std::size_t i = 0; i < items.size(); ++i) item_index[items[i].id] = i;

  for (const ParticipantPlan& pp : plans) {
    const std::vector<Occasion> known = occasions(items, pp.plan, factors);
    std::vector<std::pair<Key, TableRow>> rows;
    // (instrument block index, occasion order) -> its sub-answers and the occasion
    std::map<std::pair<std::size_t, std::size_t>, std::pair<SubAnswers, Occasion>> by_occasion;
    for (const StoredAnswer& a : answers) {
      if (a.participant != pp.participant) continue;
      const auto found = item_index.find(a.item);
      TableRow r;
      Key key;
      if (found == item_index.end()) {  // an item of another protocol revision: its raw values only
        r = row_at(a.participant, Occasion{}, factors);
        r.occasion.clear();
        r.item = a.item;
        r.scope = a.scope;
        key = Key{known.size() + 1, static_cast<double>(items.size()), a.item + "|" + a.scope};
      } else {
        const Item& item = items[found->second];
        const auto [occasion_scope, own] = split_scope(item, a.scope);
        std::size_t order = 0;
        const Occasion o = occasion_of(item, occasion_scope, known, pp.plan, order);
        r = row_at(a.participant, o, factors);
        r.item = item.id;
        r.instrument = item.instrument ? item.instrument->name : "";
        r.type = item.type ? item.type->name : "";
        r.scope = own;
        r.label = value_label(item, a.value);
        key = Key{order, static_cast<double>(found->second), own};
        if (item.instrument && own.empty())
          for (std::size_t u = 0; u < instruments.size(); ++u)
            if (instruments[u].id == item.block) {
              auto& [subs, occ] = by_occasion[{u, order}];
              subs[item.sub] = a.value;
              occ = o;
            }
      }
      if (const double* v = std::get_if<double>(&a.value)) r.number = *v;
      else r.text = std::get<std::string>(a.value);
      r.answered_at = a.answered_at;
      rows.emplace_back(std::move(key), std::move(r));
    }
    for (const auto& [where, found] : by_occasion) {
      const InstrumentUse& use = instruments[where.first];
      const std::vector<Scale> scales = use.instrument->scales(use.keys);
      const std::vector<std::optional<double>> scores = score_occasion(use, found.first);
      double last_item = 0;
      for (const std::string& id : use.items)
        if (auto it = item_index.find(id); it != item_index.end()) last_item = std::max(last_item, static_cast<double>(it->second));
      for (std::size_t s = 0; s < scales.size() && s < scores.size(); ++s) {
        if (!scores[s]) continue;
        TableRow r = row_at(pp.participant, found.second, factors);
        r.item = use.id + ":" + scales[s].id;
        r.instrument = use.instrument->name;
        r.type = "score";
        r.number = scores[s];
        r.label = scales[s].label;
        rows.emplace_back(Key{where.second, last_item + 0.5, std::to_string(s)}, std::move(r));
      }
    }
    std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [key, r] : rows) t.rows.push_back(std::move(r));
  }
  return t;
}

}  // namespace dtlab::questionnaire
