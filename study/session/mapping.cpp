// Protocol -> stage parameters (mapping.h). Every protocol value that reaches
// the scene generator or the renderer passes through this file, and the table
// in docs/session.md ("From protocol to stages") is its documentation: a change
// here changes that table in the same commit.
#include "study/session/mapping.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "study/common/version.h"
#include "study/design/design.h"
#include "study/scene/models.h"

namespace dtlab::session {

namespace {

// An error about a protocol key, at the line where the key (or the table that inherits it) is written.
Error bad(const protocol::Protocol& p, std::string field, std::string message) {
  return protocol::error_at(p, std::move(field), std::move(message));
}

// An error about a planned trial that does not fit the protocol (no protocol key to point at).
Error plan_error(const protocol::Protocol& p, std::string field, std::string message) {
  return Error{p.source_path, 0, 0, std::move(field), std::move(message)};
}

std::string task_field(const protocol::Scenario& s, const protocol::Task& t) {
  return "scenarios." + s.name + ".tasks." + t.id;
}

// The protocol key behind each generator parameter, so an error of scene::validate names a key
// the author wrote. The generator's fixed constants (walls, doors, the T2 letter, the red
// distractors) are named by the key that makes them fail: walls and doors need a large enough
// cell_size, rooms a large enough grid, the letter a large enough extent, the red distractors
// enough objects.
std::string protocol_key(const std::string& generator_field) {
  static const std::pair<const char*, const char*> kKeys[] = {
      {"abstract.objects", "objects"},           {"abstract.cube_size", "extent"},
      {"abstract.min_radius", "object_radius"},  {"abstract.max_radius", "object_radius"},
      {"abstract.target_ratio_min", "target_ratio"}, {"abstract.target_ratio_max", "target_ratio"},
      {"abstract.letters", "letters"},           {"abstract.letter_cone_radius", "extent"},
      {"abstract.letter_spacing", "extent"},     {"abstract.red_distractor_ratio_min", "objects"},
      {"abstract.red_distractor_ratio_max", "objects"},
      {"walkthrough.grid_width", "grid"},        {"walkthrough.grid_depth", "grid"},
      {"walkthrough.room_min", "grid"},          {"walkthrough.room_max", "grid"},
      {"walkthrough.cell_size", "cell_size"},    {"walkthrough.wall_thickness", "cell_size"},
      {"walkthrough.door_width", "cell_size"},   {"walkthrough.wall_height", "object_kinds"},
      {"walkthrough.objects", "objects"},        {"walkthrough.kinds", "object_kinds"},
      {"walkthrough.count_min", "count_range"},  {"walkthrough.count_max", "count_range"},
  };
  for (const auto& [g, k] : kKeys)
    if (generator_field == g) return k;
  return "";
}

// scene::validate's error as an error about the protocol key behind it (the message keeps the
// generator's own parameter name when it is not that key).
Error scene_error(const protocol::Protocol& p, const std::string& task_field, const Error& e) {
  const std::string key = protocol_key(e.field);
  if (key.empty()) return bad(p, task_field, "the scene generator refuses " + e.field + ": " + e.message);
  const std::string generator_name = e.field.substr(e.field.find('.') + 1);
  return bad(p, task_field + "." + key,
             generator_name == key ? e.message : e.message + " (the generator's " + generator_name + ")");
}

Result<std::vector<std::string>> model_kinds(const protocol::Protocol& p, const std::string& field,
                                             const std::vector<std::string>& families) {
  std::vector<std::string> kinds;
  std::set<std::string> known;
  for (const scene::ModelInfo& m : scene::model_catalogue()) known.insert(std::string(m.family));
  for (const std::string& family : families) {
    if (!known.count(family)) {
      std::string all;
      for (const auto& k : known) all += (all.empty() ? "" : ", ") + k;
      return bad(p, field, "unknown model family '" + family + "'; the model catalogue has: " + all);
    }
  }
  // Catalogue order (pets, vehicles, furniture), so the list does not depend on the file's order
  // of families and the generator sees one canonical list.
  for (const scene::ModelInfo& m : scene::model_catalogue())
    if (std::find(families.begin(), families.end(), m.family) != families.end()) kinds.emplace_back(m.kind);
  return kinds;
}

// render::validate(dt), with a refusal named by the protocol key behind it: each key's value is
// tried alone on otherwise default settings, so the error names the key the author wrote
// whatever the renderer calls its field.
}  // namespace

scene::Kind scene_kind(protocol::ScenarioKind kind) {
  return kind == protocol::ScenarioKind::abstract ? scene::Kind::abstract : scene::Kind::walkthrough;
}

scene::Task scene_task(protocol::TaskType type) {
  switch (type) {
    case protocol::TaskType::count_targets: return scene::Task::T1;
    case protocol::TaskType::identify_letter: return scene::Task::T2;
    case protocol::TaskType::find_unique: return scene::Task::T3;
    case protocol::TaskType::count_kind: return scene::Task::T4;
  }
  return scene::Task::T1;
}

Result<scene::Params> scene_params(const protocol::Protocol& p, const protocol::Scenario& scenario,
                                   const protocol::Task& task) {
  const std::string field = task_field(scenario, task);
  const protocol::SceneParams& s = task.scene;
  scene::Params out;
  const scene::Task t = scene_task(task.type);
  if (s.kind == protocol::ScenarioKind::abstract) {
    scene::AbstractParams& a = out.abstract;
    // The generator always places all four primitives; a protocol that lists fewer asks for
    // something it cannot do, so it is refused rather than silently ignored.
    std::set<std::string> listed(s.object_kinds.begin(), s.object_kinds.end());
    const std::set<std::string> all{"box", "cone", "sphere", "torus"};
    if (listed != all)
      return bad(p, field + ".object_kinds",
                 "the ABSTRACT generator places spheres, cones, boxes and tori; a subset is not supported "
                 "(list all four: [\"sphere\", \"cone\", \"box\", \"torus\"])");
    a.objects = s.objects;
    a.cube_size = static_cast<float>(s.extent);
    a.min_radius = static_cast<float>(s.object_radius.min);
    a.max_radius = static_cast<float>(s.object_radius.max);
    a.target_ratio_min = s.target_ratio.min;
    a.target_ratio_max = s.target_ratio.max;
    a.letters.clear();
    for (const std::string& l : s.letters) {
      if (l.size() != 1) return bad(p, field + ".letters", "'" + l + "' is not one letter of C K R X Y");
      a.letters += l[0];
    }
    if (t == scene::Task::T2 && a.letters.empty())
      return bad(p, field + ".letters", "an identify-letter task needs at least one of C K R X Y");
    if (a.letters.empty()) a.letters = scene::AbstractParams{}.letters;  // unused outside T2
    if (Status st = scene::validate(a, t); !st) return scene_error(p, field, st.error());
  } else {
    scene::WalkthroughParams& w = out.walkthrough;
    w.grid_width = s.grid_width;
    w.grid_depth = s.grid_height;
    w.cell_size = static_cast<float>(s.cell_size);
    w.objects = s.objects;
    auto kinds = model_kinds(p, field + ".object_kinds", s.object_kinds);
    if (!kinds) return kinds.error();
    w.kinds = std::move(kinds.value());
    w.count_min = s.count_range.min;
    w.count_max = s.count_range.max;
    if (Status st = scene::validate(w, t); !st) return scene_error(p, field, st.error());
  }
  if (!scene::task_belongs_to(t, scene_kind(s.kind)))
    return bad(p, field + ".type", "task " + std::string(scene::task_name(t)) + " does not belong to a " +
                                       std::string(protocol::to_string(s.kind)) + " scenario");
  return out;
}

Result<render::FrameSettings> frame_settings(const protocol::Protocol& p, const protocol::Rendering& r, int width,
                                             int height) {
  if (width < 1 || height < 1) throw std::invalid_argument("session::frame_settings: viewport must be at least 1x1");
  const std::string field = "rendering." + r.name;
  const technique::Technique* method = technique::find(r.method);
  if (method == nullptr)
    return bad(p, field + ".method", "the renderer has no method '" + r.method + "' (" + technique::names() + ")");
  render::FrameSettings f;
  f.occlusion_culling = r.keys.culling.occlusion_culling;
  // Each key group the method reads sets its part (study/technique), and names the key it cannot take.
  if (const auto problem = technique::frame_settings(*method, r.keys, width, height, f))
    return bad(p, field + "." + problem->key, problem->message);
  return f;
}

Result<TrialSetup> trial_setup(const protocol::Protocol& p, const design::PlannedTrial& trial) {
  const std::string where = "plan.trials[" + std::to_string(trial.position) + "]";
  if (trial.levels.size() != p.factors.size())
    return plan_error(p, where + ".levels", "the trial has " + std::to_string(trial.levels.size()) + " factor levels, the protocol " +
                                         std::to_string(p.factors.size()) + " factors");
  std::vector<int> levels;
  for (std::size_t f = 0; f < p.factors.size(); ++f) {
    const auto& [factor, level] = trial.levels[f];
    const auto& lv = p.factors[f].levels;
    const auto it = std::find(lv.begin(), lv.end(), level);
    if (factor != p.factors[f].name || it == lv.end())
      return plan_error(p, where + ".levels", "'" + factor + "=" + level + "' is not a level of factor '" + p.factors[f].name + "'");
    levels.push_back(static_cast<int>(it - lv.begin()));
  }
  TrialSetup s;
  s.condition = protocol::condition_index(p, levels);
  if (s.condition < 0) return plan_error(p, where + ".levels", "no condition has these levels");
  const protocol::Condition& c = p.conditions[static_cast<std::size_t>(s.condition)];
  s.scenario = &p.scenarios[static_cast<std::size_t>(c.scenario)];
  s.rendering = &p.renderings[static_cast<std::size_t>(c.rendering)];
  s.task = protocol::find_task(*s.scenario, trial.task);
  if (!s.task) return plan_error(p, where + ".task", "scenario '" + s.scenario->name + "' has no task '" + trial.task + "'");
  s.kind = scene_kind(s.task->scene.kind);
  s.scene_task = scene_task(s.task->type);
  auto params = scene_params(p, *s.scenario, *s.task);
  if (!params) return params.error();
  s.params = std::move(params.value());
  return s;
}

Result<scene::Scene> trial_scene(const TrialSetup& setup, const design::PlannedTrial& trial) {
  return scene::generate(setup.kind, setup.scene_task, trial.seed, setup.params);
}

store::Answer answer_key(const scene::Answer& a) {
  switch (a.task) {
    case scene::Task::T1:
    case scene::Task::T4: return store::Count{a.count};
    case scene::Task::T2: return store::Letter{std::string(1, a.letter)};
    case scene::Task::T3: return store::Position{a.position.x, a.position.y};
  }
  return store::Count{0};
}

store::StudyInfo study_info(const protocol::Protocol& p) {
  store::StudyInfo s;
  s.protocol_id = p.id;
  s.protocol_text = p.source_text;
  s.protocol_sha256 = p.sha256;
  s.design_sha256 = protocol::design_sha256(p);
  s.software_version = std::string(version_string());
  s.order_rows = design::order_rows(p);
  for (const protocol::Factor& f : p.factors) s.factors.push_back(f.name);
  return s;
}

Result<design::Plan> ledger_plan(store::StudyReader& reader, const protocol::Protocol& p, const std::string& participant) {
  auto ledger = reader.ledger();
  if (!ledger) return ledger.error();
  const auto e = std::find_if(ledger->begin(), ledger->end(),
                              [&](const store::LedgerEntry& x) { return x.participant == participant; });
  if (e == ledger->end())
    return Error{reader.path(), 0, 0, "participant", "unknown participant \"" + participant + "\"",
                 ErrorKind::not_found};
  auto revisions = reader.revisions();
  if (!revisions) return revisions.error();
  auto sessions = reader.sessions();
  if (!sessions) return sessions.error();
  std::int64_t study = e->study_id;  // the revision their session began under, else the one they enrolled under
  for (const auto& s : *sessions)
    if (s.participant == participant) study = s.study_id;
  const std::string design = protocol::design_sha256(p);
  for (const store::Revision& r : *revisions)
    if (r.study_id == study && r.design_sha256 != design)
      return Error{reader.path(), 0, 0, "studies.design",
                   "participant \"" + participant + "\" was enrolled under protocol \"" + r.protocol_id +
                       "\" (SHA-256 " + r.protocol_sha256 + ", design revision " + std::to_string(r.design_revision) +
                       "), whose design differs from this protocol's (" + p.source_path + ", SHA-256 " + p.sha256 +
                       "); use the protocol the database records",
                   ErrorKind::conflict};
  const int rows = design::order_rows(p);
  if (e->order_row >= rows)
    return Error{reader.path(), 0, 0, "participants.order_row",
                 "participant \"" + participant + "\" has order row " + std::to_string(e->order_row) +
                     " but the protocol has " + std::to_string(rows) + (rows == 1 ? " row" : " rows"),
                 ErrorKind::conflict};
  return design::make_plan(p, e->index, e->order_row);
}

store::OpenOptions open_options(bool allow_protocol_change) {
  store::OpenOptions o;
  o.allow_protocol_change = allow_protocol_change;
  o.design_hash_of = &protocol::design_sha256_of_text;
  return o;
}

store::ReadOptions read_options() {
  store::ReadOptions o;
  o.design_hash_of = &protocol::design_sha256_of_text;
  return o;
}

}  // namespace dtlab::session
