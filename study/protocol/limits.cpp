// documented() (limits.h): the table docs/protocol.md is tested against, built
// from the same constants the reader checks with.
#include "study/protocol/limits.h"

#include <algorithm>
#include <array>
#include <vector>

#include "study/questionnaire/instrument.h"
#include "study/technique/technique.h"

namespace dtlab::protocol::limits {

namespace {

constexpr Documented ints(std::string_view section, std::string_view key, Ints r) {
  return {section, key, static_cast<double>(r.min), static_cast<double>(r.max)};
}
constexpr Documented numbers(std::string_view section, std::string_view key, Numbers r) {
  return {section, key, r.min, r.max};
}

constexpr std::array kDocumented{
    ints("top level", "format", kFormat),
    ints("top level", "participants", kParticipants),
    ints("top level", "master_seed", kMasterSeed),
    numbers("session", "time_limit_s", kSessionTimeLimit),
    numbers("training", "time_limit_s", kTrainingTimeLimit),
    ints("training", "practice_trials", kPracticeTrials),
    ints("breaks", "every_trials", kBreakEvery),
    numbers("breaks", "min_s", kBreakSeconds),
    numbers("breaks", "max_s", kBreakSeconds),
    ints("factors", "levels", kLevels),
    ints("order", "rows", kRandomRows),
    ints("order", "nested_rows", kRandomRows),
    ints("scenarios", "objects", kAbstractObjects),
    ints("scenarios", "objects", kWalkthroughObjects),
    numbers("scenarios", "extent", kExtent),
    numbers("scenarios", "object_radius", kObjectRadius),
    numbers("scenarios", "target_ratio", kTargetRatio),
    ints("scenarios", "letters", kLetters),
    ints("scenarios", "grid", kGrid),
    numbers("scenarios", "cell_size", kCellSize),
    ints("scenarios", "count_range", kCountRange),
    ints("tasks", "trials", kTrials),
    ints("demographics", "range", kDemographicRange),
    ints("demographics", "options", kDemographicOptions),
    ints("reference_results", "participants", kReferenceParticipants),
    numbers("reference_results", "mean", kReferenceMean),
    numbers("reference_results", "sd", kReferenceSd),
};

// The questionnaire's ranged keys, as the item types and instruments declare them, in registry
// order (docs/protocol.md has a table per type in the same order).
void add_questionnaire(std::vector<Documented>& out) {
  namespace q = dtlab::questionnaire;
  const auto add = [&](const q::KeySpec& k) {
    if (k.kind == q::KeyKind::text || k.kind == q::KeyKind::choice || k.kind == q::KeyKind::boolean) return;
    out.push_back({"questionnaire", k.name, k.min, k.max});
  };
  for (const q::ItemType* t : q::item_types())
    for (const q::KeySpec& k : t->keys) add(k);
  for (const q::Instrument* i : q::instruments())
    for (const q::KeySpec& k : i->keys) add(k);
}

// The rendering methods' ranged keys, as their key groups declare them, in the registry's order.
void add_rendering(std::vector<Documented>& out) {
  using Kind = technique::KeySpec::Kind;
  for (const technique::KeyGroup* g : technique::key_groups())
    for (const technique::KeySpec& k : g->keys)
      if (k.kind == Kind::number || k.kind == Kind::integer) out.push_back({"rendering", k.name, k.min, k.max});
}

}  // namespace

std::span<const Documented> documented() {
  static const std::vector<Documented> all = [] {
    std::vector<Documented> v(kDocumented.begin(), kDocumented.end());
    // The rendering keys, as the registry's key groups declare them, after the tasks.
    std::vector<Documented> r;
    add_rendering(r);
    v.insert(std::find_if(v.begin(), v.end(), [](const Documented& d) { return d.section == "demographics"; }),
             r.begin(), r.end());
    // After the rendering keys, where docs/protocol.md's [questionnaire.*] section stands.
    auto at = std::find_if(v.begin(), v.end(), [](const Documented& d) { return d.section == "demographics"; });
    std::vector<Documented> q;
    add_questionnaire(q);
    v.insert(at, q.begin(), q.end());
    return v;
  }();
  return all;
}

}  // namespace dtlab::protocol::limits
