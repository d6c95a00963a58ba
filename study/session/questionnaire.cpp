// The questionnaire (session.h): the occasions of a plan, the items asked at
// each expanded into questions, the depth test's static view and its answer
// key, and the session's recorded trials read back through the store for
// the responder's memory.
// Guarantees: the same (protocol, enrollment index, viewport) gives the same
// questions, view and pairs; the depth-test key is geometry (distance from
// the eye), never what a renderer shows. Never: writes to the store.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "study/design/seeds.h"
#include "study/render/camera.h"
#include "study/common/random.h"
#include "study/session/session.h"
#include "study/store/read.h"

namespace dtlab::session {

std::vector<Question> expand_questionnaire(const protocol::Protocol& p, const questionnaire::Occasion& o) {
  const questionnaire::DesignNames names = protocol::design_names(p);
  std::vector<Question> out;
  for (const protocol::QuestionnaireItem& item : p.questionnaire) {
    if (!questionnaire::asked_at(item, o)) continue;
    for (Question& q : questionnaire::expand(item, names)) out.push_back(std::move(q));
  }
  return out;
}

std::vector<questionnaire::Occasion> questionnaire_occasions(const protocol::Protocol& p, const design::Plan& plan) {
  std::vector<questionnaire::PlanPoint> points;
  points.reserve(plan.trials.size());
  for (const design::PlannedTrial& t : plan.trials) points.push_back({t.position, t.block, t.task, t.levels});
  std::vector<std::string> factors;
  for (const protocol::Factor& f : p.factors) factors.push_back(f.name);
  return questionnaire::occasions(p.questionnaire, points, factors);
}

Result<DepthTestKey> depth_test_view(const protocol::Protocol& p, const protocol::QuestionnaireItem& item,
                                     int enrollment_index, const Viewport& vp, std::vector<Question>& questions) {
  const std::string field = "questionnaire." + item.id;
  auto bad = [&](const std::string& f, const std::string& m) { return protocol::error_at(p, f, m); };
  const std::string& scenario_name = item.text("scenario");
  const std::string& rendering_name = item.text("rendering");
  const int pairs_wanted = static_cast<int>(item.integer("pairs"));
  const protocol::Scenario* scenario = find_scenario(p, scenario_name);
  const protocol::Rendering* rendering = find_rendering(p, rendering_name);
  if (!scenario || scenario->tasks.empty()) return bad(field + ".scenario", "no scenario '" + scenario_name + "' with tasks");
  if (!rendering) return bad(field + ".rendering", "no rendering '" + rendering_name + "'");
  if (scenario->scene.kind != protocol::ScenarioKind::walkthrough)
    return bad(field + ".scenario", "scenario '" + scenario->name + "' is kind = \"" +
                                        std::string(protocol::to_string(scenario->scene.kind)) +
                                        "\"; the depth test needs a walkthrough scenario (objects at eye level in rooms)");

  int item_position = 0;
  for (std::size_t i = 0; i < p.questionnaire.size(); ++i)
    if (&p.questionnaire[i] == &item) item_position = static_cast<int>(i);
  const std::uint64_t seed = design::depth_test_seed(p.master_seed, static_cast<std::uint64_t>(enrollment_index),
                                                     static_cast<std::uint64_t>(item_position));
  // The scene of the scenario's first task: its objects are what the participant saw all session.
  const protocol::Task& task = scenario->tasks.front();
  auto params = scene_params(p, *scenario, task);
  if (!params) return params.error();
  auto sc = scene::generate(scene_kind(task.scene.kind), scene_task(task.type), seed, params.value());
  if (!sc) return sc.error();
  auto frame = frame_settings(p, *rendering, vp.width, vp.height);
  if (!frame) return frame.error();

  DepthTestKey key;
  key.view.item = item.id;
  key.view.scene = std::move(sc.value());
  key.view.frame = std::move(frame.value());
  const scene::Scene& s = key.view.scene;
  scene::CameraStart cam = s.camera;
  const float aspect = static_cast<float>(vp.width) / static_cast<float>(vp.height);
  const double half_h = 0.8 * std::atan(std::tan(0.5 * cam.fov_y) * aspect);  // inner 80% of the horizontal field

  // Objects (the placed models, not the building) in view from the start, for yaw step k of 16,
  // half a cell to ten cells away (2 to 40 units in the reference's 4-unit cells).
  const double near = 0.5 * task.scene.cell_size, far = 10.0 * task.scene.cell_size;
  struct Seen {
    std::uint32_t id;
    double dist;
  };
  auto in_view = [&](double yaw) {
    std::vector<Seen> seen;
    const glm::dvec2 fwd(-std::sin(yaw), -std::cos(yaw));  // yaw 0 looks along -z, yaw pi/2 along -x
    for (const scene::Object& o : s.objects) {
      if (!o.target) continue;
      const glm::dvec2 d(o.transform[3].x - cam.position.x, o.transform[3].z - cam.position.z);
      const double dist = std::hypot(d.x, d.y);
      if (dist < near || dist > far) continue;
      const double ang = std::acos(std::clamp(glm::dot(d / dist, fwd), -1.0, 1.0));
      if (ang <= half_h) seen.push_back({o.id, dist});
    }
    return seen;
  };
  // Yaw steps by how many objects they show (most first, ties to the lower step).
  std::vector<std::pair<int, int>> steps;
  for (int k = 0; k < 16; ++k) steps.emplace_back(-static_cast<int>(in_view(k * 6.283185307179586 / 16).size()), k);
  std::sort(steps.begin(), steps.end());

  Stream rng(seed);
  for (const double lo : {1.2, 1.05}) {
    const double hi = lo == 1.2 ? 2.0 : 3.0;
    for (const auto& [neg, k] : steps) {
      if (-neg < 2 * pairs_wanted) break;
      const double yaw = k * 6.283185307179586 / 16;
      std::vector<Seen> seen = in_view(yaw);
      // Seeded shuffle, then greedy disjoint pairs whose distance ratio lies in [lo, hi].
      rng.shuffle(seen);
      std::vector<std::pair<Seen, Seen>> pairs;
      std::vector<char> used(seen.size(), 0);
      for (std::size_t i = 0; i < seen.size() && static_cast<int>(pairs.size()) < pairs_wanted; ++i) {
        if (used[i]) continue;
        for (std::size_t j = i + 1; j < seen.size(); ++j) {
          if (used[j]) continue;
          const double r = std::max(seen[i].dist, seen[j].dist) / std::min(seen[i].dist, seen[j].dist);
          if (r >= lo && r <= hi) {
            used[i] = used[j] = 1;
            pairs.emplace_back(seen[i], seen[j]);
            break;
          }
        }
      }
      if (static_cast<int>(pairs.size()) < pairs_wanted) continue;
      cam.yaw = static_cast<float>(yaw);
      key.view.camera = cam;
      for (Question& q : questions) {
        if (q.item != &item) continue;
        const auto& [a, b] = pairs[static_cast<std::size_t>(q.pair - 1)];
        q.object_a = a.id;
        q.object_b = b.id;
      }
      for (const auto& [a, b] : pairs) key.closer.push_back(a.dist < b.dist ? a.id : b.id);
      return key;
    }
  }
  return bad(field + ".pairs", "no view from the start cell shows " + std::to_string(pairs_wanted) +
                                   " pairs of objects at distinguishable distances; lower pairs or place more "
                                   "objects (scenario '" + scenario->name + "', task " + task.id + ")");
}

std::optional<glm::vec2> depth_test_marker(const DepthTestView& v, std::uint32_t object, const Viewport& vp) {
  for (const scene::Object& o : v.scene.objects) {
    if (o.id != object) continue;
    const scene::Mesh& m = v.scene.meshes[o.mesh];
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& vertex : m.vertices) {
      lo = glm::min(lo, vertex.position);
      hi = glm::max(hi, vertex.position);
    }
    const float w = static_cast<float>(vp.width), h = static_cast<float>(vp.height);
    const render::Camera cam = render::camera_from_start(v.camera, w / h);
    const glm::vec4 c = cam.view_proj() * o.transform * glm::vec4((lo + hi) * 0.5f, 1.0f);
    if (c.w <= 0) return std::nullopt;
    return glm::vec2((c.x / c.w * 0.5f + 0.5f) * w, (1.0f - (c.y / c.w * 0.5f + 0.5f)) * h);
  }
  return std::nullopt;
}

Result<std::vector<RecordedTrial>> recorded_trials(store::Store& store, const std::string& participant_id) {
  auto rows = store.read().trials(participant_id);
  if (!rows) return rows.error();
  std::vector<RecordedTrial> out;
  for (const store::TrialRow& t : *rows) out.push_back(RecordedTrial{t.planned, t.completion_s, t.answer.has_value()});
  return out;
}

}  // namespace dtlab::session
