// Protocol -> stage parameters (study/session/mapping.h): every value of the
// reference protocol arrives where docs/session.md says, and every value a
// stage cannot take is an Error naming the protocol field.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <algorithm>
#include <cmath>

#include "study/design/design.h"
#include "study/scene/models.h"
#include "study/session/mapping.h"

namespace dtlab::session {
namespace {

protocol::Protocol reference() {
  auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/elmqvist2008.toml");
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().to_string());
  return p.value();
}

const protocol::Task& task(const protocol::Protocol& p, const std::string& id, const protocol::Scenario** scenario) {
  for (const auto& s : p.scenarios)
    for (const auto& t : s.tasks)
      if (t.id == id) {
        *scenario = &s;
        return t;
      }
  throw std::runtime_error("no task " + id);
}

TEST(Mapping, KindsAndTasks) {
  EXPECT_EQ(scene_kind(protocol::ScenarioKind::abstract), scene::Kind::abstract);
  EXPECT_EQ(scene_kind(protocol::ScenarioKind::walkthrough), scene::Kind::walkthrough);
  const std::pair<protocol::TaskType, scene::Task> cases[] = {
      {protocol::TaskType::count_targets, scene::Task::T1},
      {protocol::TaskType::identify_letter, scene::Task::T2},
      {protocol::TaskType::find_unique, scene::Task::T3},
      {protocol::TaskType::count_kind, scene::Task::T4},
  };
  for (const auto& [type, t] : cases) EXPECT_EQ(scene_task(type), t) << protocol::to_string(type);
}

// Reference values (protocols/elmqvist2008.toml) arrive in the generator's parameters.
TEST(Mapping, ReferenceAbstractParameters) {
  const protocol::Protocol p = reference();
  for (const char* id : {"T1", "T2"}) {
    const protocol::Scenario* s = nullptr;
    const protocol::Task& t = task(p, id, &s);
    auto params = scene_params(p, *s, t);
    ASSERT_TRUE(params.ok()) << params.error().to_string();
    const scene::AbstractParams& a = params->abstract;
    EXPECT_EQ(a.objects, 200) << id;
    EXPECT_EQ(a.cube_size, 100.0f) << id;
    EXPECT_EQ(a.min_radius, 3.0f) << id;
    EXPECT_EQ(a.max_radius, 6.0f) << id;
    EXPECT_EQ(a.target_ratio_min, 0.10) << id;
    EXPECT_EQ(a.target_ratio_max, 0.20) << id;
    EXPECT_EQ(a.letters, "CKRXY") << id;
  }
}

TEST(Mapping, ReferenceWalkthroughParameters) {
  const protocol::Protocol p = reference();
  std::vector<std::string> every_model;
  for (const auto& m : scene::model_catalogue()) every_model.emplace_back(m.kind);
  for (const char* id : {"T3", "T4"}) {
    const protocol::Scenario* s = nullptr;
    const protocol::Task& t = task(p, id, &s);
    auto params = scene_params(p, *s, t);
    ASSERT_TRUE(params.ok()) << params.error().to_string();
    const scene::WalkthroughParams& w = params->walkthrough;
    EXPECT_EQ(w.grid_width, 16) << id;
    EXPECT_EQ(w.grid_depth, 16) << id;
    EXPECT_EQ(w.cell_size, 4.0f) << id;
    EXPECT_EQ(w.objects, 50) << id;
    EXPECT_EQ(w.count_min, 3) << id;
    EXPECT_EQ(w.count_max, 8) << id;
    // pet + vehicle + furniture = the whole catalogue, in catalogue order.
    EXPECT_EQ(w.kinds, every_model) << id;
  }
}

TEST(Mapping, FamiliesSelectTheirModelsOnly) {
  protocol::Protocol p = reference();
  const protocol::Scenario* s = nullptr;
  protocol::Task t = task(p, "T4", &s);
  t.scene.object_kinds = {"vehicle", "pet"};  // file order must not matter
  auto params = scene_params(p, *s, t);
  ASSERT_TRUE(params.ok()) << params.error().to_string();
  std::vector<std::string> expected;
  for (const auto& m : scene::model_catalogue())
    if (m.family == "pet" || m.family == "vehicle") expected.emplace_back(m.kind);
  EXPECT_EQ(params->walkthrough.kinds, expected);
}

TEST(Mapping, ReferenceRenderings) {
  const protocol::Protocol p = reference();
  struct Case {
    const char* name;
    render::Method method;
  };
  for (const Case c : {Case{"off", render::Method::standard}, Case{"on", render::Method::dt_seed}}) {
    const auto it = std::find_if(p.renderings.begin(), p.renderings.end(), [&](const auto& r) { return r.name == c.name; });
    ASSERT_NE(it, p.renderings.end());
    auto f = frame_settings(p, *it, 800, 600);
    ASSERT_TRUE(f.ok()) << f.error().to_string();
    EXPECT_EQ(f->method, c.method) << c.name;
    if (c.method == render::Method::standard) {  // reads no dynamic transparency key: the renderer's defaults
      const render::DtSettings none;
      EXPECT_EQ(f->dt.gradient_px, none.gradient_px);
      EXPECT_EQ(f->dt.r1_guard, none.r1_guard);
      EXPECT_EQ(f->dt.mode, none.mode);
      continue;
    }
    EXPECT_FLOAT_EQ(f->dt.alpha_start, 0.1f) << c.name;
    EXPECT_FLOAT_EQ(f->dt.alpha_target, 0.3f) << c.name;
    EXPECT_EQ(f->dt.mask_resolution, 128) << c.name;
    EXPECT_EQ(f->dt.shape, render::MaskShape::outline) << c.name;
    EXPECT_EQ(f->dt.mode, render::DtMode::passive) << c.name;
    EXPECT_EQ(f->dt.layer_limit, 0) << c.name;
    EXPECT_TRUE(f->dt.r1_guard) << c.name << ": the protocol's r1_guard is on unless it says false";
    // n = 8 mask pixels of a 128-pixel mask over 800 x 600, as the renderer converts it.
    EXPECT_FLOAT_EQ(f->dt.gradient_px, render::gradient_px_from_mask_pixels(8.0f, 128, 800, 600)) << c.name;
    auto small = frame_settings(p, *it, 160, 120);
    ASSERT_TRUE(small.ok());
    EXPECT_FLOAT_EQ(small->dt.gradient_px, render::gradient_px_from_mask_pixels(8.0f, 128, 160, 120));
    EXPECT_LT(small->dt.gradient_px, f->dt.gradient_px) << "the gradient scales with the viewport";
  }
}

// r1_guard = false reaches the renderer: the article's algorithm as printed, for the dt methods.
TEST(Mapping, R1GuardOffIsTheArticleAsPrinted) {
  protocol::Protocol p = reference();
  for (protocol::Rendering& r : p.renderings) r.keys.guard.r1_guard = false;
  for (const protocol::Rendering& r : p.renderings) {
    auto f = frame_settings(p, r, 800, 600);
    ASSERT_TRUE(f.ok()) << f.error().to_string();
    EXPECT_FALSE(f->dt.r1_guard) << r.name;
  }
}

// The active searchlight covers the same share of the view on every screen: searchlight_radius x
// the view's height (0.2 x 600 = 120, the article's screen; 0.2 x 1024 = 204.8), centred.
TEST(Mapping, TheSearchlightScalesWithTheView) {
  protocol::Protocol p = reference();
  protocol::Rendering on = p.renderings[1];
  on.keys.dt.mode = "active";
  auto f = frame_settings(p, on, 800, 600);
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  EXPECT_EQ(f->dt.mode, render::DtMode::active);
  EXPECT_FLOAT_EQ(f->dt.searchlight_radius, 120.0f);
  EXPECT_FLOAT_EQ(f->dt.searchlight_center.x, 400.0f);
  auto big = frame_settings(p, on, 1280, 1024);
  ASSERT_TRUE(big.ok());
  EXPECT_FLOAT_EQ(big->dt.searchlight_radius, 204.8f);
  on.keys.dt.searchlight_radius = 0.5;
  EXPECT_FLOAT_EQ(frame_settings(p, on, 1280, 1024)->dt.searchlight_radius, 512.0f);
}

// Values a stage cannot take: each an Error naming the protocol field.
// A mask finer than the view can show is drawn at the view's full resolution (the same picture at
// less cost; regression: a 4096 mask at 800 x 600 ran at 4096 x 4096 and took minutes a frame under
// dt-seed); the gradient keeps the width the protocol's mask gives it. 128 is always kept.
TEST(Mapping, AMaskFinerThanTheViewIsTheViewsOwnResolution) {
  protocol::Protocol p = reference();
  protocol::Rendering r = p.renderings[1];
  r.keys.dt.mask_resolution = 4096;
  auto fine = frame_settings(p, r, 800, 600);
  ASSERT_TRUE(fine.ok()) << fine.error().to_string();
  EXPECT_EQ(fine->dt.mask_resolution, 0);
  EXPECT_NEAR(fine->dt.gradient_px, 8.0f * std::sqrt(800.0f * 600.0f) / 4096.0f, 1e-3f);
  r.keys.dt.mask_resolution = 800;  // the longer side: kept
  EXPECT_EQ(frame_settings(p, r, 800, 600)->dt.mask_resolution, 800);
  r.keys.dt.mask_resolution = 128;  // finer than a 16 x 16 view, but always kept
  EXPECT_EQ(frame_settings(p, r, 16, 16)->dt.mask_resolution, 128);
}

// The lens table of the shipped comparison protocol becomes the renderer's LensSettings key by key;
// an absent length is twice the radius; fixed mode does not follow the cursor.
TEST(Mapping, LensRendering) {
  auto loaded = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/lens-vs-dt.toml");
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  protocol::Protocol p = std::move(loaded.value());
  const protocol::Rendering* r = protocol::find_rendering(p, "lens");
  ASSERT_NE(r, nullptr);
  auto f = frame_settings(p, *r, 800, 600);
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  EXPECT_EQ(f->method, render::Method::lens);
  EXPECT_EQ(f->lens.shape, render::LensShape::cone);
  EXPECT_EQ(f->lens.style, render::LensStyle::eraser);
  EXPECT_FLOAT_EQ(f->lens.radius, 20.0f);
  EXPECT_FLOAT_EQ(f->lens.distance, 237.6f);
  EXPECT_FLOAT_EQ(f->lens.length, 100.0f);
  EXPECT_TRUE(f->lens.follows_cursor);
  EXPECT_EQ(f->lens.center, glm::vec2(400.0f, 300.0f));
  protocol::Rendering fixed = *r;
  fixed.keys.dt.mode = "fixed";
  fixed.keys.lens.length = 0.0;  // absent
  fixed.keys.lens.shape = "box";
  f = frame_settings(p, fixed, 800, 600);
  ASSERT_TRUE(f.ok());
  EXPECT_FALSE(f->lens.follows_cursor);
  EXPECT_EQ(f->lens.shape, render::LensShape::box);
  EXPECT_FLOAT_EQ(f->lens.length, 40.0f);
  fixed.keys.lens.style = "glass";
  f = frame_settings(p, fixed, 800, 600);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error().field, "rendering.lens.style");
}

// The vdt table of the shipped comparison protocol becomes the renderer's VdtSettings key by key;
// a value the renderer refuses is an error naming the protocol's key.
TEST(Mapping, VdtRendering) {
  auto loaded = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/vdt-vs-dt.toml");
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  protocol::Protocol p = std::move(loaded.value());
  const protocol::Rendering* r = protocol::find_rendering(p, "vdt");
  ASSERT_NE(r, nullptr);
  protocol::Rendering edited = *r;
  edited.keys.vdt.falloff = 0.25;
  edited.keys.vdt.opaque_alpha = 0.75;
  edited.keys.vdt.background_alpha = 0.125;
  auto f = frame_settings(p, edited, 800, 600);
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  EXPECT_EQ(f->method, render::Method::vdt);
  EXPECT_FLOAT_EQ(f->vdt.falloff, 0.25f);
  EXPECT_FLOAT_EQ(f->vdt.opaque_alpha, 0.75f);
  EXPECT_FLOAT_EQ(f->vdt.background_alpha, 0.125f);
  edited.keys.vdt.opaque_alpha = 2.0;
  f = frame_settings(p, edited, 800, 600);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error().field, "rendering.vdt.opaque_alpha");
}

// occlusion_culling = true in a [rendering.*] table turns the renderer's flag on, for a lens too;
// absent, it stays off (the default).
TEST(Mapping, OcclusionCullingKey) {
  std::string text;
  {
    std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/lens-vs-dt.toml");
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  auto plain = protocol::load_protocol_text(text, "lens-vs-dt.toml");
  ASSERT_TRUE(plain.ok()) << plain.error().to_string();
  for (const auto& r : plain->renderings) EXPECT_FALSE(frame_settings(*plain, r, 800, 600)->occlusion_culling);
  const auto at = text.find("method = \"lens\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "occlusion_culling = true\n");
  auto loaded = protocol::load_protocol_text(text, "lens-vs-dt.toml");
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  const protocol::Rendering* r = protocol::find_rendering(*loaded, "lens");
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(r->keys.culling.occlusion_culling);
  auto f = frame_settings(*loaded, *r, 800, 600);
  ASSERT_TRUE(f.ok());
  EXPECT_TRUE(f->occlusion_culling);
  EXPECT_EQ(f->method, render::Method::lens);
}

// The screen-door table of the shipped comparison protocol: the dynamic-transparency keys as for
// dt-seed, plus the mask side and generation; a side the renderer lacks names its key.
TEST(Mapping, ScreenDoorRendering) {
  auto loaded = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/screen-door-vs-dt.toml");
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  protocol::Protocol p = std::move(loaded.value());
  const protocol::Rendering* r = protocol::find_rendering(p, "screen-door");
  ASSERT_NE(r, nullptr);
  auto f = frame_settings(p, *r, 800, 600);
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  EXPECT_EQ(f->method, render::Method::screen_door);
  EXPECT_EQ(f->screen_door.mask_side, 8);
  EXPECT_EQ(f->screen_door.masks, render::ScreenDoorMasks::tabular);
  EXPECT_FLOAT_EQ(f->dt.alpha_target, 0.3f);
  EXPECT_FLOAT_EQ(f->dt.alpha_start, 0.1f);
  // 8 mask pixels of a 128 mask at 800 x 600: 8 sqrt(800 x 600) / 128 = 43.30 output pixels.
  EXPECT_NEAR(f->dt.gradient_px, 43.30f, 0.01f);
  protocol::Rendering other = *r;
  other.keys.screen_door.screen_door_mask = 32;
  other.keys.screen_door.screen_door_generation = "pixel-tree";
  f = frame_settings(p, other, 800, 600);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->screen_door.mask_side, 32);
  EXPECT_EQ(f->screen_door.masks, render::ScreenDoorMasks::pixel_tree);
  other.keys.screen_door.screen_door_mask = 12;
  f = frame_settings(p, other, 800, 600);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error().field, "rendering.screen-door.screen_door_mask");
  other.keys.screen_door.screen_door_mask = 8;
  other.keys.screen_door.screen_door_generation = "blue-noise";
  f = frame_settings(p, other, 800, 600);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error().field, "rendering.screen-door.screen_door_generation");
}

TEST(Mapping, UnsupportedValuesNameTheField) {
  const protocol::Protocol ref = reference();
  struct Case {
    const char* what;
    void (*mutate)(protocol::Protocol&);
    const char* task;        // "" = a rendering case
    std::string field;
  };
  const Case cases[] = {
      {"unknown model family", [](protocol::Protocol& p) { p.scenarios[1].tasks[0].scene.object_kinds = {"pet", "robot"}; },
       "T3", "scenarios.walkthrough.tasks.T3.object_kinds"},
      {"subset of primitives", [](protocol::Protocol& p) { p.scenarios[0].tasks[0].scene.object_kinds = {"sphere", "cone"}; },
       "T1", "scenarios.abstract.tasks.T1.object_kinds"},
      {"two-letter letter", [](protocol::Protocol& p) { p.scenarios[0].tasks[1].scene.letters = {"CK"}; }, "T2",
       "scenarios.abstract.tasks.T2.letters"},
      {"letter outside C K R X Y", [](protocol::Protocol& p) { p.scenarios[0].tasks[1].scene.letters = {"Q"}; }, "T2",
       "scenarios.abstract.tasks.T2.letters"},
      {"objects too large for the cube", [](protocol::Protocol& p) { p.scenarios[0].tasks[0].scene.object_radius = {3, 60}; },
       "T1", "scenarios.abstract.tasks.T1.object_radius"},
      {"too many objects for the grid", [](protocol::Protocol& p) { p.scenarios[1].tasks[1].scene.objects = 400; }, "T4",
       "scenarios.walkthrough.tasks.T4.objects"},
      {"unknown method", [](protocol::Protocol& p) { p.renderings[1].method = "x-ray"; }, "", "rendering.on.method"},
      {"unknown mask shape", [](protocol::Protocol& p) { p.renderings[1].keys.dt.mask_shape = "star"; }, "", "rendering.on.mask_shape"},
      {"unknown mode", [](protocol::Protocol& p) { p.renderings[1].keys.dt.mode = "sometimes"; }, "", "rendering.on.mode"},
      {"aT out of range", [](protocol::Protocol& p) { p.renderings[1].keys.dt.aT = 1.5; }, "", "rendering.on.aT"},
      // Regression: aT = 1 passed the reader (0..1) and failed mid-session naming DtSettings.alpha_target;
      // the article needs aT below 1 (Algorithm 3 finds the target by alpha != 1).
      {"aT = 1", [](protocol::Protocol& p) { p.renderings[1].keys.dt.aT = 1.0; }, "", "rendering.on.aT"},
      {"a0 = 1", [](protocol::Protocol& p) { p.renderings[1].keys.dt.a0 = 1.0; }, "", "rendering.on.a0"},
      {"layer limit the renderer cannot count", [](protocol::Protocol& p) { p.renderings[1].keys.dt.layer_limit = 64; }, "",
       "rendering.on.layer_limit"},
  };
  // Line of the first "key =" after the header of the field's scenario or rendering table in the
  // reference file: where an error about the key must point (a task's key it does not set is
  // written in its scenario).
  const auto line_of = [&](const std::string& field) {
    const std::string& text = ref.source_text;
    const std::size_t dot = field.find('.', field.find('.') + 1);
    const std::size_t table = text.find("\n[" + field.substr(0, dot) + "]");
    const std::size_t at = text.find("\n" + field.substr(field.rfind('.') + 1) + " =", table);
    if (table == std::string::npos || at == std::string::npos) return 0;
    return 2 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  };
  for (const Case& c : cases) {
    protocol::Protocol p = ref;
    c.mutate(p);
    Error e;
    if (*c.task) {
      const protocol::Scenario* s = nullptr;
      const protocol::Task& t = task(p, c.task, &s);
      auto r = scene_params(p, *s, t);
      ASSERT_FALSE(r.ok()) << c.what;
      e = r.error();
    } else {
      auto r = frame_settings(p, p.renderings[1], 800, 600);
      ASSERT_FALSE(r.ok()) << c.what;
      e = r.error();
    }
    EXPECT_EQ(e.field, c.field) << c.what << ": " << e.to_string();
    EXPECT_EQ(e.file, p.source_path) << c.what;
    // Every error points into the file: at the key if the file writes it, else at its table.
    EXPECT_GE(e.line, 1) << c.what << ": " << e.to_string();
    EXPECT_GE(e.column, 1) << c.what << ": " << e.to_string();
    EXPECT_EQ(e.line, line_of(c.field)) << c.what << ": " << e.to_string();
    EXPECT_FALSE(e.message.empty()) << c.what;
    EXPECT_EQ(e.message.find("DtSettings"), std::string::npos) << c.what << ": names an internal field: " << e.message;
  }
}

// Every planned trial of every participant maps to its condition's scenario, task and rendering.
TEST(Mapping, TrialSetupFollowsThePlan) {
  const protocol::Protocol p = reference();
  for (int k = 0; k < 4; ++k) {
    const design::Plan plan = design::make_plan(p, k);
    for (const auto& t : plan.trials) {
      auto s = trial_setup(p, t);
      ASSERT_TRUE(s.ok()) << s.error().to_string();
      EXPECT_EQ(s->task->id, t.task);
      EXPECT_EQ(s->rendering->method, t.method);
      const auto& c = p.conditions[static_cast<std::size_t>(s->condition)];
      for (std::size_t f = 0; f < p.factors.size(); ++f)
        EXPECT_EQ(p.factors[f].levels[static_cast<std::size_t>(c.levels[f])], t.levels[f].second);
      EXPECT_EQ(s->scenario->name, t.levels[1].second);  // factor 2 is the scenario
    }
  }
  design::PlannedTrial bad = design::make_plan(p, 0).trials.front();
  bad.levels[0].second = "sometimes";
  auto r = trial_setup(p, bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, "plan.trials[1].levels");
  bad = design::make_plan(p, 0).trials.front();
  bad.task = "T9";
  r = trial_setup(p, bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, "plan.trials[1].task");
}

// A task is found by its id within its own scenario only (protocol::find_task).
TEST(Mapping, FindTaskLooksInItsScenario) {
  const protocol::Protocol p = reference();
  const protocol::Scenario* abstract = protocol::find_scenario(p, "abstract");
  ASSERT_NE(abstract, nullptr);
  ASSERT_EQ(abstract->tasks.size(), 2u);
  EXPECT_EQ(protocol::find_task(*abstract, "T1"), &abstract->tasks[0]);
  EXPECT_EQ(protocol::find_task(*abstract, "T2"), &abstract->tasks[1]);
  EXPECT_EQ(protocol::find_task(*abstract, "T3"), nullptr);  // a walkthrough task
  EXPECT_EQ(protocol::find_task(*abstract, "t1"), nullptr);  // ids are case-sensitive
}

TEST(Mapping, AnswerKeysAndStudyInfo) {
  scene::Answer a;
  a.task = scene::Task::T1;
  a.count = 27;
  EXPECT_EQ(std::get<store::Count>(answer_key(a)).n, 27);
  a.task = scene::Task::T2;
  a.letter = 'K';
  EXPECT_EQ(std::get<store::Letter>(answer_key(a)).letter, "K");
  a.task = scene::Task::T3;
  a.position = {12.5f, -3.25f};
  const auto pos = std::get<store::Position>(answer_key(a));
  EXPECT_EQ(pos.x, 12.5);
  EXPECT_EQ(pos.z, -3.25);
  a.task = scene::Task::T4;
  a.count = 5;
  EXPECT_EQ(std::get<store::Count>(answer_key(a)).n, 5);

  const protocol::Protocol p = reference();
  const store::StudyInfo s = study_info(p);
  EXPECT_EQ(s.protocol_id, "elmqvist2008");
  EXPECT_EQ(s.protocol_sha256, p.sha256);
  EXPECT_EQ(s.protocol_text, p.source_text);
  EXPECT_EQ(s.order_rows, 4);
  EXPECT_EQ(s.factors, (std::vector<std::string>{"transparency", "scenario"}));
}

}  // namespace
}  // namespace dtlab::session
