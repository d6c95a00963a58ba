// The shipped protocols load, validate without errors and carry the reference
// study's values (STUDY.md); the scene-parameter cascade task -> scenario ->
// default works; the protocol records its text and SHA-256.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "study/common/hash.h"
#include "study/protocol/protocol.h"

namespace {

using namespace dtlab::protocol;

const std::string kReference = DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml";
const std::string kPilot = DTLAB_SOURCE_DIR "/protocols/pilot.toml";
const std::string kLens = DTLAB_SOURCE_DIR "/protocols/lens-vs-dt.toml";
const std::string kVdt = DTLAB_SOURCE_DIR "/protocols/vdt-vs-dt.toml";

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string all(const std::vector<dtlab::Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) s += d.to_string() + "\n";
  return s;
}

class ShippedProtocol : public testing::TestWithParam<std::string> {};

TEST_P(ShippedProtocol, ValidatesWithoutErrorsOrWarnings) {
  const auto diags = validate_protocol_file(GetParam());
  EXPECT_TRUE(diags.empty()) << all(diags);
  const auto p = load_protocol(GetParam());
  ASSERT_TRUE(p.ok()) << p.error().to_string();
  EXPECT_EQ(p->source_path, GetParam());
  EXPECT_EQ(p->source_text, read(GetParam()));
  EXPECT_EQ(p->sha256, dtlab::sha256_hex(read(GetParam())));
  EXPECT_EQ(p->sha256.size(), 64u);
}

INSTANTIATE_TEST_SUITE_P(Protocols, ShippedProtocol, testing::Values(kReference, kPilot, kLens, kVdt));

TEST(ReferenceProtocol, HasTheDesignOfStudyMd) {
  const auto r = load_protocol(kReference);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Protocol& p = *r;
  EXPECT_EQ(p.id, "elmqvist2008");
  EXPECT_EQ(p.participants, 16);
  EXPECT_EQ(p.session_time_limit_s, 3600.0);
  EXPECT_EQ(p.training.time_limit_s, 300.0);
  EXPECT_EQ(p.training.practice_trials, 0);
  ASSERT_EQ(p.factors.size(), 2u);
  EXPECT_EQ(p.factors[0].name, "transparency");
  EXPECT_EQ(p.factors[0].role, FactorRole::rendering);
  EXPECT_EQ(p.factors[0].levels, (std::vector<std::string>{"off", "on"}));
  EXPECT_EQ(p.factors[1].name, "scenario");
  EXPECT_EQ(p.factors[1].role, FactorRole::scenario);
  EXPECT_EQ(p.factors[1].levels, (std::vector<std::string>{"abstract", "walkthrough"}));
  ASSERT_EQ(p.conditions.size(), 4u);
  EXPECT_EQ(p.conditions[0].name, "off/abstract");
  EXPECT_EQ(p.conditions[1].name, "off/walkthrough");
  EXPECT_EQ(p.conditions[2].name, "on/abstract");
  EXPECT_EQ(p.conditions[3].name, "on/walkthrough");
  EXPECT_EQ(p.order.unit, OrderUnit::conditions);
  EXPECT_EQ(p.order.scheme, Scheme::latin_square);
  EXPECT_EQ(declared_order_rows(p), 4);
}

TEST(ReferenceProtocol, HasTheScenesAndTasksOfStudyMd) {
  const auto r = load_protocol(kReference);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Protocol& p = *r;
  ASSERT_EQ(p.scenarios.size(), 2u);
  const Scenario& a = p.scenarios[0];
  EXPECT_EQ(a.name, "abstract");
  EXPECT_EQ(a.scene.kind, ScenarioKind::abstract);
  EXPECT_EQ(a.scene.objects, 200);
  EXPECT_EQ(a.scene.extent, 100.0);
  EXPECT_EQ(a.scene.object_kinds, (std::vector<std::string>{"sphere", "cone", "box", "torus"}));
  EXPECT_EQ(a.scene.target_ratio.min, 0.10);
  EXPECT_EQ(a.scene.target_ratio.max, 0.20);
  ASSERT_EQ(a.tasks.size(), 2u);
  EXPECT_EQ(a.tasks[0].id, "T1");
  EXPECT_EQ(a.tasks[0].type, TaskType::count_targets);
  EXPECT_EQ(a.tasks[0].trials, 3);
  EXPECT_EQ(a.tasks[1].id, "T2");
  EXPECT_EQ(a.tasks[1].type, TaskType::identify_letter);
  EXPECT_EQ(a.tasks[1].scene.letters, (std::vector<std::string>{"C", "K", "R", "X", "Y"}));
  EXPECT_EQ(a.tasks[1].scene.objects, 200);  // inherited from the scenario

  const Scenario& w = p.scenarios[1];
  EXPECT_EQ(w.name, "walkthrough");
  EXPECT_EQ(w.scene.kind, ScenarioKind::walkthrough);
  EXPECT_EQ(w.scene.grid_width, 16);
  EXPECT_EQ(w.scene.grid_height, 16);
  EXPECT_EQ(w.scene.objects, 50);
  EXPECT_EQ(w.scene.object_kinds, (std::vector<std::string>{"pet", "vehicle", "furniture"}));
  ASSERT_EQ(w.tasks.size(), 2u);
  EXPECT_EQ(w.tasks[0].id, "T3");
  EXPECT_EQ(w.tasks[0].type, TaskType::find_unique);
  EXPECT_EQ(w.tasks[1].id, "T4");
  EXPECT_EQ(w.tasks[1].type, TaskType::count_kind);
  EXPECT_EQ(w.tasks[1].scene.count_range.min, 3);
  EXPECT_EQ(w.tasks[1].scene.count_range.max, 8);
  for (const auto& sc : p.scenarios)
    for (const auto& t : sc.tasks) EXPECT_EQ(t.trials, 3) << t.id;
}

TEST(ReferenceProtocol, HasTheRenderingAndQuestionnaireOfStudyMd) {
  const auto r = load_protocol(kReference);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Protocol& p = *r;
  ASSERT_EQ(p.renderings.size(), 2u);
  EXPECT_EQ(p.renderings[0].name, "off");
  EXPECT_EQ(p.renderings[0].method, "standard");
  const Rendering& on = p.renderings[1];
  EXPECT_EQ(on.name, "on");
  EXPECT_EQ(on.method, "dt-seed");
  EXPECT_EQ(on.keys.dt.mask_resolution, 128);
  EXPECT_EQ(on.keys.dt.mask_shape, "outline");
  EXPECT_EQ(on.keys.dt.mode, "passive");
  EXPECT_LT(on.keys.dt.a0, on.keys.dt.aT);  // "a low start alpha a0 ... a higher threshold opacity aT" (V.4)
  // Conditions pick the rendering of their transparency level and the scenario of their scenario level.
  for (const auto& c : p.conditions) {
    EXPECT_EQ(p.renderings[c.rendering].name, p.factors[0].levels[c.levels[0]]);
    EXPECT_EQ(p.scenarios[c.scenario].name, p.factors[1].levels[c.levels[1]]);
  }
  ASSERT_EQ(p.questionnaire.size(), 4u);
  EXPECT_EQ(p.questionnaire[0].type->name, "rating");
  EXPECT_EQ(p.questionnaire[0].range("scale"), (dtlab::questionnaire::NumberPair{0, 4}));
  EXPECT_EQ(p.questionnaire[0].strings("per"), (std::vector<std::string>{"scenario", "transparency"}));
  EXPECT_EQ(p.questionnaire[1].type->name, "choice");
  // The factor's levels, then the neutral option (the study's "overall preference, or none").
  EXPECT_EQ(p.questionnaire[1].strings("options"), (std::vector<std::string>{"off", "on", "no preference"}));
  EXPECT_EQ(p.questionnaire[1].text("neutral"), "no preference");
  EXPECT_EQ(p.questionnaire[2].type->name, "rating");
  EXPECT_EQ(p.questionnaire[3].type->name, "depth-test");
  EXPECT_EQ(p.questionnaire[3].integer("pairs"), 3);
  EXPECT_EQ(p.questionnaire[3].text("scenario"), "walkthrough");
  EXPECT_EQ(p.questionnaire[3].text("rendering"), "on");
  for (const auto& item : p.questionnaire) EXPECT_EQ(item.when.kind, dtlab::questionnaire::When::Kind::end) << item.id;
}

// A minimal protocol: every optional key left to its documented default.
const char* kMinimal = R"(id = "mini"
title = "Minimal"
participants = 4
master_seed = 7
[factors.transparency]
role = "rendering"
levels = ["off", "on"]
[order]
scheme = "williams"
[scenarios.abstract]
kind = "abstract"
objects = 120
[scenarios.abstract.tasks.T1]
type = "count-targets"
trials = 2
[scenarios.abstract.tasks.T1b]
type = "count-targets"
trials = 1
objects = 80
target_ratio = [0.3, 0.4]
[rendering.off]
method = "standard"
[rendering.on]
method = "dt-fast"
)";

// The article's results as the reference protocol declares them (Elmqvist, Assarsson & Tsigas 2008,
// Table III and section VII), checked against the printed values.
TEST(ReferenceProtocol, DeclaresTheArticlesResults) {
  const auto r = load_protocol(kReference);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_TRUE(r->reference_results.has_value());
  const ReferenceResults& rr = *r->reference_results;
  EXPECT_EQ(rr.source, "Elmqvist, Assarsson & Tsigas (2008)");
  EXPECT_EQ(rr.label, "article");
  EXPECT_EQ(rr.participants, 16);
  EXPECT_EQ(compared_factor(*r), 0);  // transparency: means are given as {off, on}
  auto find = [&](const std::string& measure, const std::string& scope) -> const ReferenceResult* {
    for (const auto& x : rr.results)
      if (x.measure == measure && x.scope == scope) return &x;
    return nullptr;
  };
  const ReferenceResult* t4 = find("time", "T4");  // Table III: T4 140.0 (61.75) vs 40.80 (24.16), F = 48.61
  ASSERT_NE(t4, nullptr);
  EXPECT_EQ(t4->mean, (std::vector<double>{140.0, 40.80}));
  EXPECT_EQ(t4->sd, (std::vector<double>{61.75, 24.16}));
  EXPECT_EQ(t4->F, "48.61");
  EXPECT_EQ(t4->p, "< .01");
  EXPECT_EQ(t4->location, "Table III");
  const ReferenceResult* pref = find("preference", "overall");  // VII.3: .94 (.25)
  ASSERT_NE(pref, nullptr);
  EXPECT_FALSE(pref->per_level);
  EXPECT_EQ(pref->mean, std::vector<double>{0.94});
  const ReferenceResult* abstract = find("rating", "abstract");  // per scenario only p < .05
  ASSERT_NE(abstract, nullptr);
  EXPECT_TRUE(abstract->mean.empty());
  EXPECT_EQ(abstract->p, "< .05 (Friedman)");
  EXPECT_EQ(rr.results.size(), 16u);
  // Quoting a paper does not change what runs.
  const auto pilot = load_protocol(DTLAB_SOURCE_DIR "/protocols/pilot.toml");
  ASSERT_TRUE(pilot.ok());
  EXPECT_FALSE(pilot->reference_results.has_value());
}

TEST(Cascade, TaskOverridesScenarioOverridesDefault) {
  const auto r = load_protocol_text(kMinimal, "mini.toml");
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Scenario& sc = r->scenarios[0];
  EXPECT_EQ(sc.tasks[0].scene.objects, 120);                // scenario value
  EXPECT_EQ(sc.tasks[0].scene.extent, 100.0);               // built-in default
  EXPECT_EQ(sc.tasks[0].scene.target_ratio.min, 0.10);      // built-in default
  EXPECT_EQ(sc.tasks[1].scene.objects, 80);                 // task value
  EXPECT_EQ(sc.tasks[1].scene.target_ratio.min, 0.3);       // task value
  EXPECT_EQ(sc.scene.objects, 120);                         // the scenario itself is unchanged
}

TEST(Defaults, AreTheDocumentedOnes) {
  const auto r = load_protocol_text(kMinimal, "mini.toml");
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Protocol& p = *r;
  EXPECT_EQ(p.format, 1);
  EXPECT_EQ(p.description, "");
  EXPECT_EQ(p.session_time_limit_s, 3600.0);
  EXPECT_EQ(p.training.time_limit_s, 300.0);
  EXPECT_EQ(p.training.practice_trials, 0);
  EXPECT_EQ(p.order.unit, OrderUnit::conditions);
  // Without a scenario factor, the one scenario serves every condition.
  for (const auto& c : p.conditions) EXPECT_EQ(c.scenario, 0);
  const Rendering& on = p.renderings[1];
  EXPECT_EQ(on.keys.dt.a0, 0.1);
  EXPECT_EQ(on.keys.dt.aT, 0.3);
  EXPECT_EQ(on.keys.dt.gradient_width, 8);
  EXPECT_EQ(on.keys.dt.mask_resolution, 128);
  EXPECT_EQ(on.keys.dt.mask_shape, "outline");
  EXPECT_EQ(on.keys.dt.mode, "passive");
  EXPECT_EQ(on.keys.dt.layer_limit, 0);
}

TEST(SchemeRows, FollowTheDocumentedFormulas) {
  EXPECT_EQ(scheme_rows(Scheme::latin_square, 4, 0), 4);
  EXPECT_EQ(scheme_rows(Scheme::williams, 4, 0), 4);
  EXPECT_EQ(scheme_rows(Scheme::williams, 5, 0), 10);
  EXPECT_EQ(scheme_rows(Scheme::full_permutation, 4, 0), 24);
  EXPECT_EQ(scheme_rows(Scheme::full_permutation, 8, 0), 40320);
  EXPECT_EQ(scheme_rows(Scheme::random, 4, 13), 13);
  EXPECT_EQ(scheme_rows(Scheme::fixed, 4, 0), 1);
}

}  // namespace
