// session::validate_runnable (study/session/runnable.h): what `dtlab validate`
// accepts, a session can run. (1) Every documented end of every numeric key
// (docs/protocol.md), with the other keys adjusted only where the page names a
// constraint between them, passes the whole validation and its scenes
// generate. (2) Regressions, one per reproducer of issue 12: protocols that
// the reader accepted and a session then refused (after every trial, for a
// depth test) or never finished; each must now be an error at the file, line
// and field of the key at fault.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "study/design/design.h"
#include "study/protocol/limits.h"
#include "study/session/mapping.h"
#include "study/session/runnable.h"
#include "tests/common/run_cli.h"

namespace dtlab::session {
namespace {

using Edits = std::vector<std::pair<std::string, std::string>>;

std::string reference_text() { return test::read_text(DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml"); }

// The reference protocol with each `from` replaced by its `to` (each `from` must occur).
std::string edited(const Edits& edits) {
  std::string t = reference_text();
  for (const auto& [from, to] : edits) {
    const std::size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << "not in the reference: " << from;
    if (at != std::string::npos) t.replace(at, from.size(), to);
  }
  return t;
}

// 1-based line of the first occurrence of `needle` after `after` in `text`.
int line_of(const std::string& text, const std::string& needle, const std::string& after = "") {
  const std::size_t from = after.empty() ? 0 : text.find(after);
  const std::size_t at = text.find(needle, from == std::string::npos ? 0 : from);
  if (at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::string listed(const std::vector<Diagnostic>& diags) {
  std::string s;
  for (const auto& d : diags) s += d.to_string() + "\n";
  return s;
}

constexpr const char* kT1 = "type = \"count-targets\"\n";
constexpr const char* kT2 = "type = \"identify-letter\"\n";
constexpr const char* kT3 = "type = \"find-unique\"\n";
constexpr const char* kT4 = "type = \"count-kind\"\n";
std::pair<std::string, std::string> in_task(const char* type, const std::string& keys) {
  return {type, std::string(type) + keys + "\n"};
}

struct End {
  std::string what;
  Edits edits;
};

// A questionnaire key's range as its item type declares it (study/questionnaire).
protocol::limits::Ints item_key(const char* type, const char* key) {
  for (const auto& k : questionnaire::find_item_type(type)->keys)
    if (k.name == key) return {static_cast<long long>(k.min), static_cast<long long>(k.max)};
  ADD_FAILURE() << type << " has no key " << key;
  return {0, 0};
}

// A rendering key's range as its key group declares it (study/technique).
protocol::limits::Numbers rendering_key(const char* key) {
  for (const technique::KeyGroup* g : technique::key_groups())
    for (const technique::KeySpec& k : g->keys)
      if (k.name == key) return {k.min, k.max};
  ADD_FAILURE() << "no rendering key " << key;
  return {0, 0};
}

// Each documented end, written into the reference; the constraints between keys that
// docs/protocol.md names are met by the other edits of the case.
std::vector<End> documented_ends() {
  using namespace protocol::limits;
  const Ints kScale = item_key("rating", "scale"), kPairs = item_key("depth-test", "pairs");
  const Numbers kAlpha = rendering_key("a0"), kGradientWidth = rendering_key("gradient_width"),
                kMaskResolution = rendering_key("mask_resolution"), kLayerLimit = rendering_key("layer_limit");
  const auto n = [](double v) { std::ostringstream s; s.precision(17); s << v; return s.str(); };
  const auto i = [](long long v) { return std::to_string(v); };
  return {
      {"participants min", {{"participants = 16", "participants = " + i(kParticipants.min)}}},
      {"participants max", {{"participants = 16", "participants = " + i(kParticipants.max)}}},
      {"master_seed min", {{"master_seed = 20080401", "master_seed = 0"}}},
      {"master_seed max", {{"master_seed = 20080401", "master_seed = 9223372036854775807"}}},
      {"session time min", {{"time_limit_s = 3600", "time_limit_s = " + n(kSessionTimeLimit.min)}}},
      {"session time max", {{"time_limit_s = 3600", "time_limit_s = " + n(kSessionTimeLimit.max)}}},
      {"training time min", {{"time_limit_s = 300 ", "time_limit_s = " + n(kTrainingTimeLimit.min) + " "}}},
      {"training time max", {{"time_limit_s = 300 ", "time_limit_s = " + n(kTrainingTimeLimit.max) + " "}}},
      {"practice max", {{"practice_trials = 0", "practice_trials = " + i(kPracticeTrials.max)}}},
      {"random rows max", {{"scheme = \"latin-square\"", "scheme = \"random\"\nrows = " + i(kRandomRows.max)}}},
      {"nested rows max (outer x nested at most kOrderRows)",
       {{"unit = \"conditions\"", "unit = \"blocks\"\nblock_factor = \"scenario\"\nnested_scheme = \"random\"\nnested_rows = " +
                                      i(kRandomRows.max)},
        {"scheme = \"latin-square\"", "scheme = \"fixed\"\norder = [\"abstract\", \"walkthrough\"]"}}},
      {"trials max", {{"trials = 3", "trials = " + i(kTrials.max)}}},
      // ABSTRACT. One object: target_ratio must hold a whole target (T1); T2 needs its letter's cones.
      {"abstract objects min", {in_task(kT1, "objects = 1\ntarget_ratio = [1.0, 1.0]")}},
      // 2000 objects need a larger cube, and fewer targets (at most 250 in a trial).
      {"abstract objects max",
       {{"objects = 200", "objects = " + i(kAbstractObjects.max)},
        {"extent = 100.0", "extent = 1000.0"},
        {"target_ratio = [0.10, 0.20]", "target_ratio = [0.05, 0.09]"}}},
      {"extent min", {in_task(kT1, "extent = 1.0\nobject_radius = [0.01, 0.02]")}},
      {"extent max", {{"extent = 100.0", "extent = " + n(kExtent.max)}}},
      // A wider spread of radii blocks more of the cube (docs/scene.md, "Placement").
      {"object_radius min",
       {{"object_radius = [3.0, 6.0]", "object_radius = [" + n(kObjectRadius.min) + ", 6.0]"},
        {"extent = 100.0", "extent = 150.0"}}},
      {"object_radius max",
       {in_task(kT1, "objects = 1\ntarget_ratio = [1.0, 1.0]\nextent = " + n(kExtent.max) + "\nobject_radius = [3.0, " +
                         n(kObjectRadius.max) + "]")}},
      {"target_ratio min", {{"target_ratio = [0.10, 0.20]", "target_ratio = [" + n(kTargetRatio.min) + ", 0.20]"}}},
      {"target_ratio max", {in_task(kT1, "objects = 150\ntarget_ratio = [0.5, " + n(kTargetRatio.max) + "]")}},
      // WALKTHROUGH.
      // Not in T3, whose scene the depth test shows (3 pairs need 6 objects).
      {"walkthrough objects min",
       {in_task(kT4, "objects = " + i(kWalkthroughObjects.min)), {"count_range = [3, 8]", "count_range = [1, 1]"}}},
      {"walkthrough objects max",
       {{"objects = 50", "objects = " + i(kWalkthroughObjects.max)}, {"gradient_width = 8", "gradient_width = 5"}}},
      {"grid min", {{"grid = [16, 16]", "grid = [" + i(kGrid.min) + ", 16]"}, {"objects = 50", "objects = 31"}}},
      // 50 objects in 1024 cells leave the depth test's start view too few pairs: 250 do not.
      {"grid max",
       {{"grid = [16, 16]", "grid = [" + i(kGrid.max) + ", " + i(kGrid.max) + "]"},
        {"objects = 50", "objects = " + i(kWalkthroughObjects.max)},
        {"gradient_width = 8", "gradient_width = 5"}}},
      {"cell_size min (pets fit)",
       {{"cell_size = 4.0", "cell_size = " + n(kCellSize.min)},
        {"object_kinds = [\"pet\", \"vehicle\", \"furniture\"]", "object_kinds = [\"pet\"]"}}},
      {"cell_size max", {{"cell_size = 4.0", "cell_size = " + n(kCellSize.max)}}},
      {"count_range min", {{"count_range = [3, 8]", "count_range = [" + i(kCountRange.min) + ", 8]"}}},
      {"count_range max",
       {{"count_range = [3, 8]", "count_range = [3, " + i(kCountRange.max) + "]"},
        {"objects = 50", "objects = " + i(kCountRange.max)},
        {"gradient_width = 8", "gradient_width = 5"}}},
      // RENDERING. dt-seed's mask work: targets x (gradient_width + 2) x mask_resolution^2 <= 2^27.
      {"a0 max", {{"a0 = 0.1", "a0 = " + n(kAlpha.max)}, {"aT = 0.3", "aT = " + n(kAlpha.max)}}},
      {"a0, aT min", {{"a0 = 0.1", "a0 = 0.0"}, {"aT = 0.3", "aT = 0.0"}}},
      {"gradient_width min", {{"gradient_width = 8", "gradient_width = 0"}}},
      {"gradient_width max (30 targets at most)",
       {{"gradient_width = 8", "gradient_width = " + i(kGradientWidth.max)},
        {"target_ratio = [0.10, 0.20]", "target_ratio = [0.10, 0.15]"},
        {"letters = [\"C\", \"K\", \"R\", \"X\", \"Y\"]", "letters = [\"C\"]"},
        {"objects = 50", "objects = 30"}}},
      {"mask_resolution min (gradient_width at most mask_resolution)",
       {{"mask_resolution = 128", "mask_resolution = " + i(kMaskResolution.min)}}},
      {"mask_resolution max with dt-fast",
       {{"method = \"dt-seed\"", "method = \"dt-fast\""},
        {"mask_resolution = 128", "mask_resolution = " + i(kMaskResolution.max)}}},
      {"layer_limit max", {{"layer_limit = 0", "layer_limit = " + i(kLayerLimit.max)}}},
      // QUESTIONNAIRE.
      {"scale ends", {{"scale = [0, 4]", "scale = [" + i(kScale.min) + ", " + i(kScale.max) + "]"}}},
      {"pairs min", {{"pairs = 3", "pairs = " + i(kPairs.min)}}},
      {"pairs max (enough objects)",
       {{"pairs = 3", "pairs = " + i(kPairs.max)},
        {"objects = 50", "objects = " + i(kWalkthroughObjects.max)},
        {"gradient_width = 8", "gradient_width = 5"}}},
  };
}

TEST(Runnable, TheReferenceProtocolsRun) {
  for (const char* name : {"elmqvist2008.toml", "pilot.toml", "lens-vs-dt.toml", "screen-door-vs-dt.toml",
                           "vdt-vs-dt.toml"}) {
    auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/" + name);
    ASSERT_TRUE(p.ok()) << p.error().to_string();
    EXPECT_EQ(listed(validate_runnable(*p)), "") << name;
  }
}

TEST(Runnable, EveryDocumentedEndRuns) {
  for (const End& end : documented_ends()) {
    SCOPED_TRACE(end.what);
    auto p = protocol::load_protocol_text(edited(end.edits), "end.toml");
    ASSERT_TRUE(p.ok()) << end.what << ": " << p.error().to_string();
    const auto diags = validate_runnable(*p);
    EXPECT_EQ(listed(diags), "") << end.what;
    if (!diags.empty()) continue;
    // Participant 0's first trial of every task generates (the plan's own seeds).
    const design::Plan plan = design::make_plan(*p, 0);
    std::vector<std::string> done;
    for (const design::PlannedTrial& t : plan.trials) {
      if (std::find(done.begin(), done.end(), t.task) != done.end()) continue;
      done.push_back(t.task);
      auto setup = trial_setup(*p, t);
      ASSERT_TRUE(setup.ok()) << end.what << ": " << setup.error().to_string();
      auto scene = trial_scene(*setup, t);
      EXPECT_TRUE(scene.ok()) << end.what << ", trial " << t.position << ": " << scene.error().to_string();
    }
  }
}

// A refused protocol: the first error is at `line` of the edited text and names `field`.
struct Refused {
  std::string what;
  Edits edits;
  std::string field;
  std::string line_text;    // the line the error must point at: the first line holding this...
  std::string after = "";   // ...after this text
  std::string message = "";  // part of the message
};

void expect_refused(const Refused& c) {
  const std::string text = edited(c.edits);
  std::vector<Diagnostic> diags = protocol::validate_protocol_text(text, "bad.toml");
  if (!protocol::has_errors(diags)) {
    auto p = protocol::load_protocol_text(text, "bad.toml");
    ASSERT_TRUE(p.ok()) << c.what;
    diags = validate_runnable(*p);
  }
  const Diagnostic* hit = nullptr;
  for (const auto& d : diags)
    if (d.severity == Severity::error && d.where.field == c.field && !hit) hit = &d;
  ASSERT_NE(hit, nullptr) << c.what << ": no error for " << c.field << "; got:\n" << listed(diags);
  EXPECT_EQ(hit->where.file, "bad.toml") << c.what;
  EXPECT_EQ(hit->where.line, line_of(text, c.line_text, c.after)) << c.what << ": " << hit->to_string();
  EXPECT_GE(hit->where.column, 1) << c.what;
  EXPECT_NE(hit->where.message.find(c.message), std::string::npos) << c.what << ": " << hit->to_string();
}

// Issue 12's reproducers: each was "valid" and then failed in `dtlab simulate` (exit 3), failed
// after the last trial, or never finished.
TEST(Runnable, IssueReproducersAreRefusedAtTheirKey) {
  const Refused cases[] = {
      {"object_radius up to its old documented maximum 1e6",
       {{"object_radius = [3.0, 6.0]", "object_radius = [3.0, 1e6]"}},
       "scenarios.abstract.object_radius[1]", "object_radius", "", "out of range"},
      {"an object radius the cube cannot hold",
       {{"object_radius = [3.0, 6.0]", "object_radius = [3.0, 60.0]"}},
       "scenarios.abstract.tasks.T1.object_radius", "object_radius", "", "does not fit in a cube of 100"},
      {"extent = 1e6 (old documented maximum)", {{"extent = 100.0", "extent = 1e6"}},
       "scenarios.abstract.extent", "extent = 1e6", "", "out of range"},
      {"cell_size = 0.1 (old documented minimum)", {{"cell_size = 4.0", "cell_size = 0.1"}},
       "scenarios.walkthrough.cell_size", "cell_size", "", "out of range"},
      {"a cell too small for the vehicles", {{"cell_size = 4.0", "cell_size = 3.0"}},
       "scenarios.walkthrough.tasks.T3.cell_size", "cell_size", "", "does not fit in a cell"},
      {"target_ratio = [0.001, 0.001]: no whole number of targets",
       {{"target_ratio = [0.10, 0.20]", "target_ratio = [0.001, 0.001]"}},
       "scenarios.abstract.tasks.T1.target_ratio", "target_ratio", "", "no whole number"},
      {"objects = 1 at scenario level (abstract)", {{"objects = 200", "objects = 1"}},
       "scenarios.abstract.tasks.T1.target_ratio", "target_ratio", "", "of 1 object contains no whole number"},
      {"objects = 1 at task level (T2: no room for the letter)", {in_task(kT2, "objects = 1")},
       "scenarios.abstract.tasks.T2.objects", "objects = 1", "", "red_distractor_ratio"},
      {"objects = 1 at scenario level (walkthrough: T4 counts 3 to 8)", {{"objects = 50", "objects = 1"}},
       "scenarios.walkthrough.tasks.T4.count_range", "[scenarios.walkthrough.tasks.T4]", "", "exceeds objects"},
      {"objects = 2 at scenario level (walkthrough: the depth test's 3 pairs)",
       {{"objects = 50", "objects = 2"}, {"count_range = [3, 8]", "count_range = [1, 2]"}},
       "questionnaire.depth_test.pairs", "pairs = 3", "", "needs 6 distinct objects"},
      {"a depth test on an ABSTRACT scenario",
       {{"scenario = \"walkthrough\"     # one WALKTHROUGH view", "scenario = \"abstract\"     # one view"}},
       "questionnaire.depth_test.scenario", "scenario = \"abstract\"", "[questionnaire.depth_test]",
       "needs a walkthrough scenario"},
      {"pairs = 20 with 2 objects",
       {{"pairs = 3", "pairs = 20"}, {"objects = 50", "objects = 2"}, {"count_range = [3, 8]", "count_range = [1, 2]"}},
       "questionnaire.depth_test.pairs", "pairs = 20", "", "needs 40 distinct objects"},
      {"pairs = 20 with 40 objects: no view shows 20 pairs",
       {{"pairs = 3", "pairs = 20"}, {"objects = 50", "objects = 40"}},
       "questionnaire.depth_test.pairs", "pairs = 20", "", "no view"},
      {"mask_resolution = 4096 with dt-seed (a trial never finished)",
       {{"mask_resolution = 128", "mask_resolution = 4096"}},
       "rendering.on.mask_resolution", "mask_resolution = 4096", "", "mask texel writes per frame"},
      {"gradient_width wider than the mask at a 4096 x 4096 view",
       {{"gradient_width = 8", "gradient_width = 32"}, {"mask_resolution = 128", "mask_resolution = 16"}},
       "rendering.on.gradient_width", "gradient_width = 32", "", "4096x4096"},
      {"aT = 1.0 (the renderer refuses an opaque target)", {{"aT = 0.3", "aT = 1.0"}},
       "rendering.on.aT", "aT = 1.0", "", "out of range"},
      {"layer_limit = 64 (the renderer takes 60)", {{"layer_limit = 0", "layer_limit = 64"}},
       "rendering.on.layer_limit", "layer_limit = 64", "", "out of range"},
      {"random blocks of 100000 rows with a random nested scheme of 100000 rows",
       {{"unit = \"conditions\"", "unit = \"blocks\"\nblock_factor = \"scenario\"\nnested_scheme = \"random\"\n"
                                  "nested_rows = 100000"},
        {"scheme = \"latin-square\"", "scheme = \"random\"\nrows = 100000"}},
       "order.nested_rows", "nested_rows", "", "10000000000 order rows"},
      {"400 targets in one trial", {{"target_ratio = [0.10, 0.20]", "target_ratio = [0.10, 1.0]"},
                                    {"objects = 200", "objects = 400"}, {"extent = 100.0", "extent = 200.0"}},
       "scenarios.abstract.tasks.T1.target_ratio", "target_ratio", "", "at most 250"},
  };
  for (const Refused& c : cases) expect_refused(c);
}

// Answers everything at once: the first object of each pair, the lowest rating, the first option.
class Quick : public Responder {
 public:
  int trials = 0;
  Viewport viewport() const override { return {160, 120}; }
  Status train(const TaskSetSpec&) override { return {}; }
  Result<TrialOutcome> run_trial(const TrialSpec& spec) override {
    ++trials;
    TrialOutcome o;
    o.answer = answer_key(spec.scene->answer);
    o.completion_s = 1;
    o.started_at = o.ended_at = std::chrono::system_clock::now();
    return o;
  }
  Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) override {
    std::vector<QuestionAnswer> out;
    for (const Question& q : spec.questions) {
      if (q.item->type->name == "rating") out.emplace_back(q.item->range("scale").min);
      else if (q.item->type->name == "choice") out.emplace_back(q.options.front());
      else out.emplace_back(static_cast<double>(q.object_a));
    }
    return out;
  }
};

// Issue 12: a depth test that cannot be shown used to fail after the last trial, leaving the
// session `running` for good. The runner now prepares the questionnaire first: nothing begins,
// nothing is recorded, and once the protocol is fixed the same participant runs to the end.
TEST(Runnable, AQuestionnaireThatCannotBeShownStopsTheSessionBeforeItsFirstTrial) {
  const std::string db = (std::filesystem::temp_directory_path() /
                          ("dtlab_runnable_" + std::to_string(::getpid()) + ".sqlite")).string();
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db + suffix);
  const std::string text = test::read_text(DTLAB_SOURCE_DIR "/protocols/pilot.toml");
  const std::string depth = "\n[questionnaire.depth]\ntype = \"depth-test\"\nprompt = \"Which is closer?\"\n"
                            "scenario = \"abstract\"\nrendering = \"on\"\n";
  auto bad = protocol::load_protocol_text(text + depth, "bad.toml");
  ASSERT_TRUE(bad.ok()) << bad.error().to_string();
  {
    auto store = store::Store::open(db, study_info(*bad));
    ASSERT_TRUE(store.ok()) << store.error().to_string();
    Quick who;
    auto sum = run_session(store.value(), *bad, "P01", who);
    ASSERT_FALSE(sum.ok());
    EXPECT_EQ(sum.error().field, "questionnaire.depth.scenario");
    EXPECT_EQ(sum.error().file, "bad.toml");
    EXPECT_EQ(sum.error().line, line_of(text + depth, "scenario = \"abstract\""));
    EXPECT_EQ(who.trials, 0) << "no trial may run before the questionnaire is known to work";
    EXPECT_FALSE(store->session("P01").ok()) << "no session may begin";
  }
  std::string fixed_depth = depth;
  fixed_depth.replace(fixed_depth.find("abstract"), 8, "walkthrough");
  auto fixed = protocol::load_protocol_text(text + fixed_depth, "fixed.toml");
  ASSERT_TRUE(fixed.ok());
  store::OpenOptions change;
  change.allow_protocol_change = true;
  auto store = store::Store::open(db, study_info(*fixed), change);
  ASSERT_TRUE(store.ok()) << store.error().to_string();
  Quick who;
  auto sum = run_session(store.value(), *fixed, "P01", who);
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_TRUE(sum->finished);
  EXPECT_TRUE(sum->questionnaire_recorded);
  EXPECT_EQ(who.trials, 8);
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db + suffix);
}

}  // namespace
}  // namespace dtlab::session
