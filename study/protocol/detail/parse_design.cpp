// Internal: the design half of a protocol: top-level keys, [session],
// [training], [factors.*], the full factorial of conditions and [order].
// Checks that the factors cross (unique names and levels, at least two levels)
// and that the ordering scheme can order what it is asked to order; warns when
// the participant count leaves the order rows unbalanced.
#include <algorithm>
#include <limits>

#include "study/common/text.h"
#include "study/protocol/detail/parser.h"

namespace dtlab::protocol::detail {

namespace {

constexpr int kMaxFactors = static_cast<int>(limits::kFactors.max);
constexpr int kMaxConditions = static_cast<int>(limits::kConditions.max);
constexpr int kMaxPermutationItems = static_cast<int>(limits::kPermutationItems.max);  // 8! = 40320 rows

bool is_protocol_id(std::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  const auto ok_first = [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); };
  if (!ok_first(s[0])) return false;
  return std::all_of(s.begin(), s.end(), [&](char c) { return ok_first(c) || c == '_' || c == '-'; });
}

// A level name: what TOML allows as a bare key, so [scenarios.<level>] needs no quotes.
bool is_level_name(std::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::optional<Scheme> scheme_from(const std::optional<std::string>& s) {
  if (!s) return std::nullopt;
  if (*s == "latin-square") return Scheme::latin_square;
  if (*s == "williams") return Scheme::williams;
  if (*s == "full-permutation") return Scheme::full_permutation;
  if (*s == "random") return Scheme::random;
  return Scheme::fixed;
}

#define DTLAB_SCHEMES {"latin-square", "williams", "full-permutation", "random", "fixed"}

// Items ordered by a scheme: the cells of the factorial of `factors` (first slowest).
struct Items {
  std::vector<int> factors;  // indices into Protocol::factors
  int count = 1;
};

Items items_of(const Protocol& p, std::vector<int> factors) {
  Items it{std::move(factors), 1};
  for (int f : it.factors) it.count *= static_cast<int>(p.factors[f].levels.size());
  return it;
}

std::string item_name(const Protocol& p, const Items& items, int index) {
  std::vector<std::string> parts(items.factors.size());
  for (int i = static_cast<int>(items.factors.size()) - 1; i >= 0; --i) {
    const auto& levels = p.factors[items.factors[i]].levels;
    const int k = static_cast<int>(levels.size());
    parts[i] = levels[index % k];
    index /= k;
  }
  std::string s;
  for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? "/" : "") + parts[i];
  return s;
}

std::string what_is_ordered(const Protocol& p, const Items& items, bool blocks_of_factor) {
  if (blocks_of_factor) return "the " + std::to_string(items.count) + " levels of factor '" +
                               p.factors[items.factors[0]].name + "'";
  return std::to_string(items.count) + (items.count == 1 ? " condition" : " conditions");
}

// Checks that `scheme` can order `items`; false (with an error) if not.
bool check_scheme(ParseState& s, Scheme scheme, const Items& items, Pos at, const std::string& field,
                  bool blocks_of_factor) {
  const int n = items.count;
  const std::string what = what_is_ordered(s.p, items, blocks_of_factor);
  if (scheme == Scheme::williams && n < 2) {
    s.d.error(at, field, "\"williams\" needs at least 2 items to order; here it would order " + what);
    return false;
  }
  if (scheme == Scheme::full_permutation && n > kMaxPermutationItems) {
    s.d.error(at, field,
              "\"full-permutation\" of " + what + " gives " + std::to_string(n) +
                  "! rows, too many to enumerate (at most " + std::to_string(kMaxPermutationItems) +
                  " items); use \"williams\", \"latin-square\" or \"random\"");
    return false;
  }
  return true;
}

// Reads a fixed order: an array naming every item exactly once. An item is an
// inline table {factor = "level", ...} over items.factors, or, when one factor
// is ordered, just the level name.
std::optional<std::vector<int>> parse_fixed(ParseState& s, const toml::node& n, const std::string& field,
                                            const Items& items) {
  const Protocol& p = s.p;
  std::vector<std::string> names;
  for (int f : items.factors) names.push_back(p.factors[f].name);
  const std::string example =
      items.factors.size() == 1
          ? "a level of factor '" + names[0] + "'"
          : "an inline table {" + names[0] + " = \"...\", " + names[1] + " = \"...\"" +
                (names.size() > 2 ? ", ..." : "") + "}";
  const toml::array* a = n.as_array();
  if (!a) {
    s.d.error(pos_of(n), field, "expected an array of " + std::to_string(items.count) + " items, each " + example +
                                    "; got " + type_name(n));
    return std::nullopt;
  }
  std::vector<int> order;
  std::vector<int> first_at(items.count, -1);
  bool ok = true;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string ef = indexed(field, i);
    std::vector<int> level(items.factors.size(), -1);
    if (e.is_string() && items.factors.size() == 1) {
      const auto& levels = p.factors[items.factors[0]].levels;
      level[0] = find_index(levels, e.as_string()->get());
      if (level[0] < 0) {
        s.d.error(pos_of(e), ef, "no level \"" + e.as_string()->get() + "\" in factor '" + names[0] +
                                     "' (levels: " + quoted_list(levels) + ")");
        ok = false;
        continue;
      }
    } else if (const toml::table* t = e.as_table()) {
      bool item_ok = true;
      for (const auto& [k, v] : in_file_order(*t)) {
        const std::string kf = join(ef, k->str());
        const int fi = find_index(names, std::string(k->str()));
        if (fi < 0) {
          s.d.error(pos_of(*k), kf, "no ordered factor named '" + std::string(k->str()) +
                                        "'; expected keys: " + quoted_list(names));
          item_ok = false;
          continue;
        }
        if (!v->is_string()) {
          s.d.error(pos_of(*v), kf, "expected a level name (a string), got " + type_name(*v));
          item_ok = false;
          continue;
        }
        const auto& levels = p.factors[items.factors[fi]].levels;
        level[fi] = find_index(levels, v->as_string()->get());
        if (level[fi] < 0) {
          s.d.error(pos_of(*v), kf, "no level \"" + v->as_string()->get() + "\" in factor '" + names[fi] +
                                        "' (levels: " + quoted_list(levels) + ")");
          item_ok = false;
        }
      }
      for (std::size_t fi = 0; fi < names.size() && item_ok; ++fi) {
        if (!t->contains(names[fi])) {
          s.d.error(pos_of(e), ef, "missing factor '" + names[fi] + "'; each item names a level of " +
                                       quoted_list(names));
          item_ok = false;
        }
      }
      if (!item_ok) {
        ok = false;
        continue;
      }
    } else {
      s.d.error(pos_of(e), ef, "expected " + example + ", got " + type_name(e));
      ok = false;
      continue;
    }
    int index = 0;
    for (std::size_t fi = 0; fi < level.size(); ++fi)
      index = index * static_cast<int>(p.factors[items.factors[fi]].levels.size()) + level[fi];
    if (first_at[index] >= 0) {
      s.d.error(pos_of(e), ef, "\"" + item_name(p, items, index) + "\" listed twice (first at index " +
                                   std::to_string(first_at[index]) + "); a fixed order lists each item once");
      ok = false;
      continue;
    }
    first_at[index] = static_cast<int>(i);
    order.push_back(index);
  }
  if (!ok) return std::nullopt;
  for (int i = 0; i < items.count; ++i) {
    if (first_at[i] < 0) {
      s.d.error(pos_of(n), field, "\"" + item_name(p, items, i) + "\" is missing; a fixed order lists all " +
                                      std::to_string(items.count) + " items exactly once");
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  return order;
}

// Counted exactly (a random nested scheme can ask for 100000 x 100000 rows), refused before
// anything is built from it: the store keeps a count per row, and rows beyond the most
// participants a protocol can have are never used. False (with an error) if there are too many.
bool check_row_count(ParseState& s, TableReader& r, const Items& outer, const Items& nested) {
  const Ordering& o = s.p.order;
  const bool blocks = o.unit == OrderUnit::blocks;
  const std::int64_t total_rows = declared_order_rows(s.p);
  if (total_rows <= limits::kOrderRows.max) return true;
  const char* key = blocks && o.nested_scheme == Scheme::random && r.has("nested_rows") ? "nested_rows"
                    : o.scheme == Scheme::random && r.has("rows")                       ? "rows"
                                                                                        : "scheme";
  std::string how;
  if (blocks)
    how = " (" + std::to_string(scheme_rows(o.scheme, outer.count, o.rows)) + " outer x " +
          std::to_string(scheme_rows(o.nested_scheme, nested.count, o.nested_rows)) + " nested)";
  s.d.error(r.pos(key), r.field(key),
            "the ordering has " + std::to_string(total_rows) + " order rows" + how + "; at most " +
                std::to_string(limits::kOrderRows.max) + " (the most participants a protocol can have)");
  return false;
}

// Balance warnings: they do not make the protocol invalid.
void warn_balance(ParseState& s, TableReader& r) {
  const Protocol& p = s.p;
  const Ordering& o = p.order;
  if (!s.participants_ok) return;
  const std::int64_t total_rows = declared_order_rows(p);
  const std::int64_t n = p.participants;
  const std::string rows_text = count(total_rows, "order row");
  if (o.scheme == Scheme::fixed && (o.unit != OrderUnit::blocks || o.nested_scheme == Scheme::fixed) && n > 1) {
    s.d.warning(r.pos("scheme"), "order.scheme",
                "every participant gets the same order, so order effects are confounded with conditions");
  } else if (total_rows > n) {
    s.d.warning(s.participants_pos, "participants",
                "participants = " + std::to_string(n) + " is fewer than the " + rows_text + " of the ordering; " +
                    std::to_string(total_rows - n) + " rows are never used and positions are not balanced");
  } else if (n % total_rows != 0) {
    s.d.warning(s.participants_pos, "participants",
                "participants = " + std::to_string(n) + " is not a multiple of the " + rows_text +
                    " of the ordering; the first " + std::to_string(n % total_rows) +
                    " rows get one participant more and positions are not balanced");
  }
}

}  // namespace

int find_index(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

std::vector<std::string> factor_names(const Protocol& p) {
  std::vector<std::string> names;
  for (const auto& f : p.factors) names.push_back(f.name);
  return names;
}

void parse_document(const toml::table& root, ParseState& s) {
  Protocol& p = s.p;
  TableReader r(root, "", s.d, {1, 1});
  if (auto v = r.integer("format", false, limits::kFormat)) p.format = static_cast<int>(*v);
  if (auto v = r.string("id", true)) {
    if (is_protocol_id(*v))
      p.id = *v;
    else
      s.d.error(r.pos("id"), "id", "\"" + *v + "\" is not a protocol id; expected lowercase letters, digits, "
                                   "'_' or '-', starting with a letter or digit, at most 64 characters");
  }
  if (auto v = r.string("title", true)) p.title = *v;
  if (auto v = r.string("description", false, false)) p.description = *v;
  s.participants_pos = r.pos("participants");
  if (auto v = r.integer("participants", true, limits::kParticipants)) {
    p.participants = static_cast<int>(*v);
    s.participants_ok = true;
  }
  if (auto v = r.integer("master_seed", true, limits::kMasterSeed))
    p.master_seed = static_cast<std::uint64_t>(*v);

  parse_flow(r, s);
  parse_factors(r, s);
  parse_scenarios(r, s);
  parse_renderings(r, s);
  build_conditions(s);
  parse_order(r, s);
  parse_questionnaire(r, s);
  parse_demographics(r, s);
  parse_reference_results(r, s);
  r.finish();

  if (!p.conditions.empty() && s.scenarios_ok) {
    std::int64_t per_participant = 0;
    for (const auto& c : p.conditions)
      for (const auto& task : p.scenarios[c.scenario].tasks)
        per_participant += task.trials + p.training.practice_trials;
    if (per_participant > limits::kTrialsPerParticipant.max)
      s.d.error({1, 1}, "scenarios", "a participant would run " + std::to_string(per_participant) +
                                         " trials (conditions x tasks x (trials + practice_trials)); at most " +
                                         std::to_string(limits::kTrialsPerParticipant.max));
  }
}

void parse_factors(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const int errors_before = s.d.errors();
  const toml::table* t = root.table("factors", true);
  if (!t) return;
  const auto entries = in_file_order(*t);
  if (entries.empty() || static_cast<int>(entries.size()) > kMaxFactors) {
    s.d.error(root.pos("factors"), "factors",
              "declares " + std::to_string(entries.size()) + " factors; expected 1 to " +
                  std::to_string(kMaxFactors) + " tables such as [factors.transparency] with levels = [...]");
    return;
  }
  for (const auto& [k, n] : entries) {
    const std::string name(k->str());
    const std::string path = join("factors", name);
    if (!is_identifier(name))
      s.d.error(pos_of(*k), path, "factor name \"" + name + "\" is not an identifier (letters, digits, '_', "
                                  "'-', starting with a letter)");
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with levels = [...], got " + type_name(*n));
      continue;
    }
    TableReader fr(*n->as_table(), path, s.d, pos_of(*k));
    Factor f;
    f.name = name;
    if (auto role = fr.choice("role", false, {"none", "scenario", "rendering"}))
      f.role = *role == "scenario" ? FactorRole::scenario
               : *role == "rendering" ? FactorRole::rendering : FactorRole::none;
    if (auto levels = fr.strings("levels", true, limits::kLevels)) {
      const toml::array& a = *fr.node("levels")->as_array();
      for (std::size_t i = 0; i < levels->size(); ++i)
        if (!is_level_name((*levels)[i]))
          s.d.error(pos_of(*a.get(i)), indexed(fr.field("levels"), i),
                    "level name \"" + (*levels)[i] + "\" may hold only letters, digits, '_' and '-'");
      f.levels = *levels;
    }
    f.labels.assign(f.levels.size(), "");
    f.instructions.assign(f.levels.size(), "");
    if (f.levels.empty()) {  // the levels' own error says it; the wording per level cannot be checked
      fr.has("labels");
      fr.has("instructions");
    } else if (auto labels = fr.texts("labels", f.levels.size(), "level")) {
      f.labels = *labels;
      for (std::size_t i = 0; i < f.labels.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if (level_label(f, static_cast<int>(i)) == level_label(f, static_cast<int>(j)))
            s.d.error(fr.pos("labels"), indexed(fr.field("labels"), i),
                      "\"" + level_label(f, static_cast<int>(i)) + "\" is also what level '" + f.levels[j] +
                          "' reads as; participants could not tell the two apart");
    }
    if (!f.levels.empty())
      if (auto instructions = fr.texts("instructions", f.levels.size(), "level")) f.instructions = *instructions;
    fr.finish();
    const int index = static_cast<int>(p.factors.size());
    for (auto [role, slot] : {std::pair{FactorRole::scenario, &s.scenario_factor},
                              std::pair{FactorRole::rendering, &s.rendering_factor}}) {
      if (f.role != role) continue;
      if (*slot >= 0)
        s.d.error(fr.pos("role"), fr.field("role"),
                  "a second factor with role = \"" + std::string(to_string(role)) + "\" (the first is '" +
                      p.factors[*slot].name + "'); at most one factor may pick the " +
                      std::string(to_string(role)));
      else
        *slot = index;
    }
    s.factor_pos.push_back(pos_of(*k));
    s.factor_levels_pos.push_back(fr.pos("levels"));
    p.factors.push_back(std::move(f));
  }
  if (s.d.errors() != errors_before) return;
  std::int64_t cells = 1;
  for (const auto& f : p.factors) cells *= static_cast<std::int64_t>(f.levels.size());
  if (cells > kMaxConditions) {
    s.d.error(root.pos("factors"), "factors", "the factors cross into " + std::to_string(cells) +
                                                  " conditions; at most " + std::to_string(kMaxConditions));
    return;
  }
  s.factors_ok = true;
}

void build_conditions(ParseState& s) {
  Protocol& p = s.p;
  if (!s.factors_ok || !s.scenarios_ok || !s.renderings_ok) return;
  std::vector<int> all(p.factors.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const Items items = items_of(p, all);
  std::vector<std::string> scenario_names, rendering_names;
  for (const auto& sc : p.scenarios) scenario_names.push_back(sc.name);
  for (const auto& r : p.renderings) rendering_names.push_back(r.name);
  for (int c = 0; c < items.count; ++c) {
    Condition cond;
    cond.levels.assign(p.factors.size(), 0);
    int rest = c;
    for (int f = static_cast<int>(p.factors.size()) - 1; f >= 0; --f) {
      const int k = static_cast<int>(p.factors[f].levels.size());
      cond.levels[f] = rest % k;
      rest /= k;
    }
    cond.name = item_name(p, items, c);
    cond.scenario = s.scenario_factor < 0
                        ? 0
                        : find_index(scenario_names, p.factors[s.scenario_factor].levels[cond.levels[s.scenario_factor]]);
    cond.rendering = s.rendering_factor < 0
                         ? 0
                         : find_index(rendering_names,
                                      p.factors[s.rendering_factor].levels[cond.levels[s.rendering_factor]]);
    p.conditions.push_back(std::move(cond));
  }
}

void parse_order(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const toml::table* t = root.table("order", true);
  if (!t) return;
  TableReader r(*t, "order", s.d, root.pos("order"));
  const int errors_before = s.d.errors();
  const auto unit = r.choice("unit", false, {"conditions", "blocks"});
  const auto scheme = scheme_from(r.choice("scheme", true, DTLAB_SCHEMES));
  const auto rows = r.integer("rows", false, limits::kRandomRows);
  const toml::node* fixed = r.node("order");
  const auto block_factor = r.string("block_factor", false);
  const auto nested_scheme = scheme_from(r.choice("nested_scheme", false, DTLAB_SCHEMES));
  const auto nested_rows = r.integer("nested_rows", false, limits::kRandomRows);
  const toml::node* nested_fixed = r.node("nested_order");
  r.finish();
  const bool blocks = unit && *unit == "blocks";
  const bool unit_known = unit || !r.has("unit");
  const bool nested_known = nested_scheme || !r.has("nested_scheme");
  if (!blocks && unit_known) {
    for (const char* key : {"block_factor", "nested_scheme", "nested_rows", "nested_order"})
      if (r.has(key)) s.d.error(r.pos(key), r.field(key), "applies only to unit = \"blocks\"");
  }
  const auto only_for = [&](const char* key, bool applies, const char* what) {
    if (!applies && r.has(key)) s.d.error(r.pos(key), r.field(key), std::string("applies only to ") + what);
  };
  if (scheme) {
    only_for("rows", *scheme == Scheme::random, "scheme = \"random\"");
    only_for("order", *scheme == Scheme::fixed, "scheme = \"fixed\"");
    if (*scheme == Scheme::fixed && !fixed)
      s.d.error(r.pos(), "order.order", "scheme = \"fixed\" needs order = [...] listing every item once");
  }
  if (blocks && nested_scheme) {
    only_for("nested_rows", *nested_scheme == Scheme::random, "nested_scheme = \"random\"");
    only_for("nested_order", *nested_scheme == Scheme::fixed, "nested_scheme = \"fixed\"");
    if (*nested_scheme == Scheme::fixed && !nested_fixed)
      s.d.error(r.pos(), "order.nested_order",
                "nested_scheme = \"fixed\" needs nested_order = [...] listing every nested item once");
  } else if (blocks && nested_known) {
    only_for("nested_rows", false, "nested_scheme = \"random\"");
    only_for("nested_order", false, "nested_scheme = \"fixed\"");
  }
  if (!scheme || !s.factors_ok || s.d.errors() != errors_before) return;

  Ordering& o = p.order;
  o.unit = blocks ? OrderUnit::blocks : OrderUnit::conditions;
  o.scheme = *scheme;
  Items outer, nested;
  if (!blocks) {
    std::vector<int> all(p.factors.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    outer = items_of(p, all);
  } else {
    if (!block_factor) {
      s.d.error(r.pos(), "order.block_factor", "unit = \"blocks\" needs block_factor = \"<factor name>\"");
      return;
    }
    const int bf = find_index(factor_names(p), *block_factor);
    if (bf < 0) {
      s.d.error(r.pos("block_factor"), "order.block_factor",
                "no factor named '" + *block_factor + "' (factors: " + quoted_list(factor_names(p)) + ")");
      return;
    }
    o.block_factor = bf;
    outer = items_of(p, {bf});
    std::vector<int> others;
    for (int f = 0; f < static_cast<int>(p.factors.size()); ++f)
      if (f != bf) others.push_back(f);
    nested = items_of(p, others);
    if (!nested_scheme && nested.count > 1) {
      s.d.error(r.pos(), "order.nested_scheme",
                "unit = \"blocks\" needs nested_scheme to order the " + std::to_string(nested.count) +
                    " cells of " + quoted_list(factor_names(p)) + " other than '" + *block_factor +
                    "' inside each block");
      return;
    }
  }
  // Outer and nested orderings are checked independently, so both report their errors.
  bool ok = check_scheme(s, o.scheme, outer, r.pos("scheme"), "order.scheme", blocks);
  o.rows = o.scheme == Scheme::random ? static_cast<int>(rows.value_or(p.participants)) : 0;
  if (ok && o.scheme == Scheme::fixed) {
    auto order = parse_fixed(s, *fixed, "order.order", outer);
    if (order)
      o.fixed = *order;
    else
      ok = false;
  }
  if (blocks) {
    o.nested_scheme = nested_scheme.value_or(Scheme::fixed);
    const bool nested_ok = !nested_scheme || check_scheme(s, o.nested_scheme, nested, r.pos("nested_scheme"),
                                                          "order.nested_scheme", false);
    ok = ok && nested_ok;
    o.nested_rows = o.nested_scheme == Scheme::random ? static_cast<int>(nested_rows.value_or(p.participants)) : 0;
    if (nested_ok && o.nested_scheme == Scheme::fixed) {
      if (nested_fixed) {
        auto order = parse_fixed(s, *nested_fixed, "order.nested_order", nested);
        if (order)
          o.nested_fixed = *order;
        else
          ok = false;
      } else {  // a single nested cell (checked above)
        o.nested_fixed = {0};
      }
    }
  }
  if (!ok) return;

  if (check_row_count(s, r, outer, nested)) warn_balance(s, r);
}

}  // namespace dtlab::protocol::detail
