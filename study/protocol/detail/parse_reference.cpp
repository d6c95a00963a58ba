// The optional [reference_results] table: published results a study is
// compared with (docs/protocol.md, "Published results"). The report shows
// them beside its own numbers, labelled with their source, and speaks of that
// source only when the table exists. Guarantees: every measure names a known
// measure or questionnaire item, every scope a task, "overall", "counting"
// or a level (a rating's other factor),
// every per-level value a level of the compared factor, each exactly once.
// Never part of the design hash: quoting a paper does not change what runs.
#include "study/protocol/detail/parser.h"

namespace dtlab::protocol {
namespace detail {
namespace {

// mean or sd: a number (per_level = false) or a table with one number per level.
std::optional<std::vector<double>> values(TableReader& r, std::string_view key, bool per_level,
                                          const std::vector<std::string>& levels, limits::Numbers range,
                                          Diagnostics& d) {
  if (!per_level) {
    auto v = r.number(key, true, range);
    if (!v) return std::nullopt;
    return std::vector<double>{*v};
  }
  const toml::table* t = r.table(key, true);
  if (!t) return std::nullopt;
  TableReader lr(*t, r.field(key), d, r.pos(key));
  std::vector<double> out;
  bool ok = true;
  for (const auto& level : levels) {
    auto v = lr.number(level, true, range);
    ok = ok && v.has_value();
    out.push_back(v.value_or(0));
  }
  lr.finish();
  if (!ok) return std::nullopt;
  return out;
}

}  // namespace

void parse_reference_results(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const toml::table* t = root.table("reference_results", false);
  if (!t) return;
  TableReader rr(*t, "reference_results", s.d, root.pos("reference_results"));
  ReferenceResults out;
  if (auto v = rr.string("source", true)) out.source = *v;
  if (auto v = rr.string("label", false)) out.label = *v;
  if (auto v = rr.integer("participants", false, limits::kReferenceParticipants))
    out.participants = static_cast<int>(*v);
  const toml::node* rows = rr.node("results");
  rr.finish();
  const int compared = compared_factor(p);
  const std::vector<std::string> levels =
      compared >= 0 ? p.factors[static_cast<std::size_t>(compared)].levels : std::vector<std::string>{};
  std::vector<std::string> measures = {"time", "accuracy"}, scopes = {"overall", "counting"};
  for (const auto& q : p.questionnaire) measures.push_back(q.id);
  for (const auto& sc : p.scenarios)
    for (const auto& task : sc.tasks) scopes.push_back(task.id);
  for (const auto& f : p.factors)  // a questionnaire item's scope: a level of its other factor
    for (const auto& level : f.levels)
      if (find_index(scopes, level) < 0 && (compared < 0 || f.name != p.factors[static_cast<std::size_t>(compared)].name))
        scopes.push_back(level);

  const toml::array* a = rows ? rows->as_array() : nullptr;
  if (!a) {
    s.d.error(rows ? pos_of(*rows) : rr.pos(), "reference_results.results",
              "expected [[reference_results.results]] tables (at least one)" +
                  (rows ? ", got " + type_name(*rows) : std::string()));
    return;
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string path = indexed("reference_results.results", i);
    const toml::node& n = *a->get(i);
    if (!n.is_table()) {
      s.d.error(pos_of(n), path, "expected a table with measure, mean and sd, got " + type_name(n));
      continue;
    }
    TableReader r(*n.as_table(), path, s.d, pos_of(n));
    ReferenceResult res;
    if (auto v = r.choice_of("measure", true, measures)) res.measure = *v;
    if (auto v = r.choice_of("scope", false, scopes)) res.scope = *v;
    if (auto v = r.string("location", false)) res.location = *v;
    if (auto v = r.string("F", false)) res.F = *v;
    if (auto v = r.string("p", false)) res.p = *v;
    const toml::node* mean = r.node("mean");
    res.per_level = !mean || mean->is_table();
    const bool given = r.has("mean") || r.has("sd");  // neither: a published test alone (F, p)
    if (!given && res.p.empty())
      s.d.error(r.pos(), path, "a result needs mean and sd, or p");
    std::optional<std::vector<double>> m, sd;
    if (given) {
      m = values(r, "mean", res.per_level, levels, limits::kReferenceMean, s.d);
      sd = values(r, "sd", res.per_level, levels, limits::kReferenceSd, s.d);
    }
    r.finish();
    if ((given && (!m || !sd)) || res.measure.empty()) continue;
    if (given) {
      res.mean = *m;
      res.sd = *sd;
    }
    for (const auto& prev : out.results)
      if (prev.measure == res.measure && prev.scope == res.scope)
        s.d.error(r.pos(), path, "a second result for measure \"" + res.measure + "\", scope \"" + res.scope + "\"");
    out.results.push_back(std::move(res));
  }
  p.reference_results = std::move(out);
}

}  // namespace detail

int compared_factor(const Protocol& p) {
  for (std::size_t f = 0; f < p.factors.size(); ++f)
    if (p.factors[f].role == FactorRole::rendering) return static_cast<int>(f);
  for (std::size_t f = 0; f < p.factors.size(); ++f)
    if (p.factors[f].role != FactorRole::scenario) return static_cast<int>(f);
  return p.factors.empty() ? -1 : 0;
}

}  // namespace dtlab::protocol
