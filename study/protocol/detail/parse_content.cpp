// Internal: the content half of a protocol: [scenarios.*] with their tasks
// and [rendering.*] ([questionnaire.*] is parse_questionnaire.cpp). Scene parameters cascade task ->
// scenario -> built-in default for the scenario kind (docs/protocol.md).
// Checks that every level of the scenario and rendering factors has its table
// and every table belongs to a level, and that each task fits its scenario.
#include <algorithm>

#include "study/protocol/detail/parser.h"

namespace dtlab::protocol::detail {

namespace {

const std::vector<std::string> kAbstractKinds = {"sphere", "cone", "box", "torus"};
const std::vector<std::string> kWalkthroughKinds = {"pet", "vehicle", "furniture"};
const std::vector<std::string> kLetters = {"C", "K", "R", "X", "Y"};  // STUDY.md, T2 (Fig. 5)
const char* const kSceneKeys[] = {"objects",      "extent",      "grid",         "cell_size", "object_kinds",
                                  "object_radius", "target_ratio", "letters",     "count_range"};

// Built-in defaults: the reference study's values (STUDY.md) where it gives them.
SceneParams defaults_for(ScenarioKind kind) {
  SceneParams sp;
  sp.kind = kind;
  if (kind == ScenarioKind::abstract) {
    sp.objects = 200;
    sp.extent = 100.0;
    sp.object_kinds = kAbstractKinds;
    sp.object_radius = {3.0, 6.0};
    sp.target_ratio = {0.10, 0.20};
    sp.letters = kLetters;
  } else {
    sp.objects = 50;
    sp.grid_width = sp.grid_height = 16;
    sp.cell_size = 4.0;
    sp.object_kinds = kWalkthroughKinds;
    sp.count_range = {3, 8};
  }
  return sp;
}

ScenarioKind scenario_kind_of(TaskType t) {
  return t == TaskType::count_targets || t == TaskType::identify_letter ? ScenarioKind::abstract
                                                                         : ScenarioKind::walkthrough;
}

// Reads the scene keys present in a scenario or task table over `scene`.
void read_scene_keys(TableReader& r, SceneParams& scene, ParseState& s) {
  const bool abstract = scene.kind == ScenarioKind::abstract;
  const auto only = [&](const char* key, bool applies) {
    if (!applies && r.has(key))
      s.d.error(r.pos(key), r.field(key),
                std::string("applies only to ") + (abstract ? "walkthrough" : "abstract") +
                    " scenarios; this one is kind = \"" + std::string(to_string(scene.kind)) + "\"");
    return applies;
  };
  if (auto v = r.integer("objects", false, abstract ? limits::kAbstractObjects : limits::kWalkthroughObjects)) scene.objects = static_cast<int>(*v);
  if (only("extent", abstract))
    if (auto v = r.number("extent", false, limits::kExtent)) scene.extent = *v;
  if (only("grid", !abstract))
    if (auto v = r.int_pair("grid", false, limits::kGrid)) {
      scene.grid_width = v->first;
      scene.grid_height = v->second;
    }
  if (only("cell_size", !abstract))
    if (auto v = r.number("cell_size", false, limits::kCellSize)) scene.cell_size = *v;
  if (auto v = r.strings("object_kinds", false, limits::kObjectKinds, abstract ? kAbstractKinds : kWalkthroughKinds))
    scene.object_kinds = *v;
  if (only("object_radius", abstract))
    if (auto v = r.number_range("object_radius", false, limits::kObjectRadius)) scene.object_radius = *v;
  if (only("target_ratio", abstract))
    if (auto v = r.number_range("target_ratio", false, limits::kTargetRatio)) scene.target_ratio = *v;
  if (only("letters", abstract))
    if (auto v = r.strings("letters", false, limits::kLetters, kLetters)) scene.letters = *v;
  if (only("count_range", !abstract))
    if (auto v = r.int_range("count_range", false, limits::kCountRange)) scene.count_range = *v;
}

// Checks a task's final scene parameters (after the cascade) against its type.
void check_task_scene(const Task& task, Pos at, const std::string& path, ParseState& s) {
  const SceneParams& sc = task.scene;
  if (task.type == TaskType::identify_letter &&
      std::find(sc.object_kinds.begin(), sc.object_kinds.end(), "cone") == sc.object_kinds.end())
    s.d.error(at, path + ".object_kinds", "task type \"identify-letter\" draws its letter with cones; "
                                          "object_kinds must include \"cone\"");
  if (task.type == TaskType::count_kind && sc.count_range.max > sc.objects)
    s.d.error(at, path + ".count_range", "count_range max " + std::to_string(sc.count_range.max) +
                                             " exceeds objects = " + std::to_string(sc.objects));
}

// Keys of the scenario/rendering tables must be exactly the levels of the factor with that role.
bool match_levels(ParseState& s, const std::string& section, int factor, Pos section_pos,
                  const std::vector<std::pair<std::string, Pos>>& tables) {
  const Protocol& p = s.p;
  bool ok = true;
  if (factor < 0) {
    if (tables.size() != 1) {
      s.d.error(section_pos, section,
                "declares " + std::to_string(tables.size()) + " tables; without a factor with role = \"" +
                    (section == "scenarios" ? std::string("scenario") : std::string("rendering")) +
                    "\" exactly one [" + section + ".<name>] is used for every condition");
      ok = false;
    }
    return ok;
  }
  const Factor& f = p.factors[factor];
  for (const auto& [name, at] : tables) {
    if (find_index(f.levels, name) < 0) {
      s.d.error(at, join(section, name),
                "no level \"" + name + "\" in factor '" + f.name + "' (levels: " + quoted_list(f.levels) +
                    "); each [" + section + ".<level>] belongs to one level");
      ok = false;
    }
  }
  for (const auto& level : f.levels) {
    const bool found = std::any_of(tables.begin(), tables.end(), [&](const auto& t) { return t.first == level; });
    if (!found) {
      s.d.error(s.factor_levels_pos[factor], join(section, level),
                "level \"" + level + "\" of factor '" + f.name + "' has no [" + section + "." + level + "] table");
      ok = false;
    }
  }
  return ok;
}

void parse_task(const toml::key& k, const toml::node& n, const std::string& tasks_path, Scenario& sc,
                std::vector<std::pair<std::string, std::string>>& task_ids, ParseState& s) {
  const std::string id(k.str());
  const std::string path = join(tasks_path, id);
  if (!is_identifier(id))
    s.d.error(pos_of(k), path, "task id \"" + id + "\" is not an identifier (letters, digits, '_', '-')");
  for (const auto& [other, where] : task_ids)
    if (other == id) s.d.error(pos_of(k), path, "task id \"" + id + "\" is already used in " + where);
  task_ids.emplace_back(id, path);
  if (!n.is_table()) {
    s.d.error(pos_of(n), path, "expected a table [" + path + "] with type and trials, got " + type_name(n));
    return;
  }
  TableReader tr(*n.as_table(), path, s.d, pos_of(k));
  Task task;
  task.id = id;
  task.scene = sc.scene;
  const auto type = tr.choice("type", true, {"count-targets", "identify-letter", "find-unique", "count-kind"});
  if (type)
    task.type = *type == "count-targets"     ? TaskType::count_targets
                : *type == "identify-letter" ? TaskType::identify_letter
                : *type == "find-unique"     ? TaskType::find_unique
                                             : TaskType::count_kind;
  if (auto v = tr.integer("trials", true, limits::kTrials)) task.trials = static_cast<int>(*v);
  if (auto v = tr.string("instructions", false)) task.instructions = *v;
  read_scene_keys(tr, task.scene, s);
  tr.finish();
  if (!type) return;
  if (scenario_kind_of(task.type) != sc.scene.kind) {
    s.d.error(tr.pos("type"), tr.field("type"),
              "task type \"" + *type + "\" needs a " + std::string(to_string(scenario_kind_of(task.type))) +
                  " scenario; this one is kind = \"" + std::string(to_string(sc.scene.kind)) + "\"");
    return;
  }
  if (task.type != TaskType::identify_letter && tr.has("letters"))
    s.d.warning(tr.pos("letters"), tr.field("letters"), "has no effect for type = \"" + *type + "\"");
  if (task.type != TaskType::count_kind && tr.has("count_range"))
    s.d.warning(tr.pos("count_range"), tr.field("count_range"), "has no effect for type = \"" + *type + "\"");
  check_task_scene(task, tr.pos(), path, s);
  sc.tasks.push_back(std::move(task));
}

}  // namespace

void parse_scenarios(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const int errors_before = s.d.errors();
  const toml::table* t = root.table("scenarios", true);
  if (!t) return;
  std::vector<std::pair<std::string, Pos>> names;
  std::vector<std::pair<std::string, std::string>> task_ids;
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string name(k->str());
    const std::string path = join("scenarios", name);
    names.emplace_back(name, pos_of(*k));
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with kind and tasks, got " + type_name(*n));
      continue;
    }
    TableReader sr(*n->as_table(), path, s.d, pos_of(*k));
    Scenario sc;
    sc.name = name;
    const auto kind = sr.choice("kind", true, {"abstract", "walkthrough"});
    if (!kind) {  // scene keys cannot be checked without a kind; do not call them unknown
      for (const char* key : kSceneKeys) sr.has(key);
      sr.has("tasks");
      sr.finish();
      continue;
    }
    sc.scene = defaults_for(*kind == "abstract" ? ScenarioKind::abstract : ScenarioKind::walkthrough);
    read_scene_keys(sr, sc.scene, s);
    if (const toml::table* tasks = sr.table("tasks", true)) {
      const auto entries = in_file_order(*tasks);
      if (entries.empty())
        s.d.error(sr.pos("tasks"), sr.field("tasks"), "expected at least one task, e.g. [" + path + ".tasks.T1]");
      for (const auto& [tk, tn] : entries) parse_task(*tk, *tn, sr.field("tasks"), sc, task_ids, s);
    }
    sr.finish();
    p.scenarios.push_back(std::move(sc));
  }
  if (names.empty()) {
    s.d.error(root.pos("scenarios"), "scenarios", "expected at least one scenario, e.g. [scenarios.abstract]");
    return;
  }
  if (!s.factors_ok || s.d.errors() != errors_before) return;
  s.scenarios_ok = match_levels(s, "scenarios", s.scenario_factor, root.pos("scenarios"), names);
}

namespace {

// The registry's key groups read a [rendering.*] table through this: every diagnostic names the
// file, line and field as the rest of the protocol's do.
class RenderingKeys final : public technique::KeyReader {
 public:
  RenderingKeys(TableReader& rr, Diagnostics& d) : rr_(rr), d_(d) {}
  std::optional<double> number(const technique::KeySpec& k, bool required) override {
    return rr_.number(k.name, required, limits::Numbers{k.min, k.max});
  }
  std::optional<std::int64_t> integer(const technique::KeySpec& k, bool required) override {
    return rr_.integer(k.name, required,
                       limits::Ints{static_cast<std::int64_t>(k.min), static_cast<std::int64_t>(k.max)});
  }
  std::optional<std::string> choice(const technique::KeySpec& k, bool required) override {
    return rr_.choice_of(k.name, required, std::vector<std::string>(k.choices.begin(), k.choices.end()));
  }
  std::optional<bool> boolean(const technique::KeySpec& k) override { return rr_.boolean(k.name, false); }
  bool has(std::string_view key) override { return rr_.has(key); }
  void error(std::string_view key, std::string message) override {
    d_.error(rr_.pos(key), rr_.field(key), std::move(message));
  }
  void warning(std::string_view key, std::string message) override {
    d_.warning(rr_.pos(key), rr_.field(key), std::move(message));
  }

 private:
  TableReader& rr_;
  Diagnostics& d_;
};

std::vector<std::string> method_names() {
  std::vector<std::string> out;
  for (const technique::Technique* t : technique::all()) out.emplace_back(t->name);
  return out;
}

// One [rendering.*] table: its method, then every key group of the registry in turn.
Rendering parse_rendering(TableReader& rr, const std::string& name, ParseState& s) {
  Rendering r;
  r.name = name;
  if (auto v = rr.choice_of("method", true, method_names())) r.method = *v;
  const technique::Technique& method = *technique::find(r.method);
  RenderingKeys keys(rr, s.d);
  for (const technique::KeyGroup* g : technique::key_groups()) g->parse(keys, method, r.keys);
  if (r.keys.culling.occlusion_culling && !s.p.scenarios.empty() &&
      std::none_of(s.p.scenarios.begin(), s.p.scenarios.end(),
                   [](const Scenario& sc) { return sc.scene.kind == ScenarioKind::walkthrough; }))
    s.d.warning(rr.pos("occlusion_culling"), rr.field("occlusion_culling"),
                "has no effect without a walkthrough scenario (occlusion culling needs a floor plan)");
  rr.finish();
  return r;
}

}  // namespace

void parse_renderings(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const int errors_before = s.d.errors();
  const toml::table* t = root.table("rendering", true);
  if (!t) return;
  std::vector<std::pair<std::string, Pos>> names;
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string name(k->str());
    const std::string path = join("rendering", name);
    names.emplace_back(name, pos_of(*k));
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with method = \"...\", got " + type_name(*n));
      continue;
    }
    TableReader rr(*n->as_table(), path, s.d, pos_of(*k));
    p.renderings.push_back(parse_rendering(rr, name, s));
  }
  if (names.empty()) {
    s.d.error(root.pos("rendering"), "rendering", "expected at least one rendering, e.g. [rendering.off]");
    return;
  }
  if (!s.factors_ok || s.d.errors() != errors_before) return;
  s.renderings_ok = match_levels(s, "rendering", s.rendering_factor, root.pos("rendering"), names);
}

}  // namespace dtlab::protocol::detail
