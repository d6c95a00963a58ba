// `dtlab render` run as a separate process (DTLAB_BINARY), protocol form:
// trial N (1-based, the position `dtlab plan` lists) of participant K's plan
// renders the scene `dtlab scene` gives for
// the plan's seed (same content hash) with the method of the trial's
// transparency level, and writes a PNG. The two forms do not mix; a wrong
// combination, a trial past the plan's end, and every out-of-range value
// (camera, seed, mask parameters) exits 2 with a message naming the option.
// --db/--participant takes K from the study database's ledger.
// Small images (64 x 48) keep each run well under a second of rendering.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <ostream>
#include <regex>
#include <sstream>
#include <string>

#include "study/protocol/protocol.h"
#include "study/session/mapping.h"
#include "study/store/store.h"
#include "tests/common/run_cli.h"

namespace {

namespace fs = std::filesystem;
using dtlab::test::CliOutcome;
using dtlab::test::run_dtlab;

const std::string kReference = std::string("'") + DTLAB_SOURCE_DIR + "/protocols/elmqvist2008.toml'";
const std::string kAbstract = "--scene abstract --task T1 --seed 1 --method dt-fast";

fs::path png_path(const std::string& tag) {
  return fs::temp_directory_path() / ("dtlab_render_cli_" + std::to_string(getpid()) + "_" + tag + ".png");
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

nlohmann::json plan_of(int index) {
  const CliOutcome r = run_dtlab("plan " + kReference + " --index " + std::to_string(index) + " --json");
  EXPECT_EQ(r.rc, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

// The content hash `dtlab scene` prints for (kind, task, seed).
std::string scene_hash(const std::string& kind, const std::string& task, std::uint64_t seed) {
  const CliOutcome r =
      run_dtlab("scene --scene " + kind + " --task " + task + " --seed " + std::to_string(seed) + " --json");
  EXPECT_EQ(r.rc, 0) << r.err;
  return nlohmann::json::parse(r.out).value("hash", std::string("missing"));
}

TEST(RenderCli, PlanTrialRendersThePlannedSceneWithTheLevelsMethod) {
  const int index = 1;
  const nlohmann::json plan = plan_of(index);
  ASSERT_EQ(plan["trials"].size(), 24u);
  bool saw_off = false, saw_on = false;
  // One trial of each transparency level and of each scenario: the first trial of every block.
  for (std::size_t n = 0; n < plan["trials"].size(); ++n) {
    const auto& t = plan["trials"][n];
    if (n > 0 && plan["trials"][n - 1]["block"] == t["block"]) continue;
    const std::string level = t["levels"]["transparency"];
    const std::string scenario = t["levels"]["scenario"];
    const fs::path out = png_path(std::to_string(n));
    const CliOutcome r = run_dtlab("render --protocol " + kReference + " --index " + std::to_string(index) +
                                   " --trial " + std::to_string(n + 1) + " --width 64 --height 48 --out '" +
                                   out.string() + "' --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    SCOPED_TRACE("trial " + std::to_string(n) + " " + level + "/" + scenario);
    EXPECT_EQ(j["method"], level == "on" ? "dt-seed" : "standard");  // elmqvist2008.toml [rendering.*]
    EXPECT_EQ(j["scene"], scenario);
    EXPECT_EQ(j["task"], t["task"]);
    EXPECT_EQ(j["seed"], t["seed"]);
    EXPECT_EQ(j["scene_hash"], scene_hash(scenario, t["task"], t["seed"].get<std::uint64_t>()));
    EXPECT_EQ(j["trial"]["position"], t["position"]);
    EXPECT_EQ(j["trial"]["trial"], n + 1) << "--trial is the plan's 1-based position";
    EXPECT_EQ(j["trial"]["index"], index);
    EXPECT_TRUE(j["gl_errors"].empty());
    EXPECT_GT(fs::file_size(out), 8u);
    fs::remove(out);
    (level == "on" ? saw_on : saw_off) = true;
  }
  EXPECT_TRUE(saw_on);
  EXPECT_TRUE(saw_off);
}

TEST(RenderCli, DbParticipantTakesTheEnrollmentIndexFromTheLedger) {
  const fs::path db = fs::temp_directory_path() / ("dtlab_render_cli_" + std::to_string(getpid()) + ".sqlite");
  fs::remove(db);
  {
    const auto p = dtlab::protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/elmqvist2008.toml");
    ASSERT_TRUE(p.ok()) << p.error().to_string();
    auto store = dtlab::store::Store::open(db.string(), dtlab::session::study_info(*p));
    ASSERT_TRUE(store.ok()) << store.error().to_string();
    ASSERT_TRUE(store->enroll("first").ok());
    ASSERT_TRUE(store->enroll("second").ok());  // enrollment index 1
  }
  const nlohmann::json plan = plan_of(1);
  const int n = 7;
  const fs::path out = png_path("db");
  const CliOutcome r = run_dtlab("render --protocol " + kReference + " --db '" + db.string() +
                                 "' --participant second --trial " + std::to_string(n + 1) +
                                 " --width 64 --height 48 --out '" + out.string() + "' --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["trial"]["index"], 1);
  EXPECT_EQ(j["trial"]["participant"], "second");
  EXPECT_EQ(j["seed"], plan["trials"][n]["seed"]);
  EXPECT_EQ(j["method"], plan["trials"][n]["method"]);
  const CliOutcome unknown = run_dtlab("render --protocol " + kReference + " --db '" + db.string() +
                                       "' --participant nobody --trial 1 --out '" + out.string() + "'");
  EXPECT_EQ(unknown.rc, 1) << unknown.err;
  EXPECT_NE(unknown.err.find("nobody"), std::string::npos) << unknown.err;
  fs::remove(out);
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(db.string() + suffix);
}

// ABSTRACT T1 seed 7 at 160 x 120 rendered with `method` (and its options) into `out`: the targets'
// visible pixels summed, and the passes that ran.
std::pair<long, nlohmann::json> visible(const std::string& method, const fs::path& out) {
  const CliOutcome r = run_dtlab("render --scene abstract --task T1 --seed 7 --width 160 --height 120 --method " +
                                 method + " --out '" + out.string() + "' --json");
  EXPECT_EQ(r.rc, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  long n = 0;
  for (const auto& t : j["targets"]) n += t["visible_pixels"].get<long>();
  EXPECT_TRUE(j["gl_errors"].empty());
  return {n, j["passes"]};
}

// `dtlab render` draws what a session draws (issue 26): the R1 guard is on unless --no-r1-guard asks
// for the article's algorithm as printed. ABSTRACT T1 seed 31 at 800 x 600 has a target that is
// wholly visible under standard and that the algorithm as printed hides completely (it stands in a
// farther target's gradient); with the guard, as in a session, it stays visible.
TEST(RenderCli, DefaultsDrawWhatASessionDrawsAndNoR1GuardTheArticleAsPrinted) {
  const auto targets = [](const std::string& args, const fs::path& out) {
    const CliOutcome r = run_dtlab("render --scene abstract --task T1 --seed 31 " + args + " --out '" + out.string() +
                                   "' --json");
    EXPECT_EQ(r.rc, 0) << r.err;
    return nlohmann::json::parse(r.out)["targets"];
  };
  const fs::path standard_png = png_path("r1-standard"), session_png = png_path("r1-default"),
                 guard_png = png_path("r1-guard"), printed_png = png_path("r1-printed");
  const auto standard = targets("--method standard", standard_png);
  const auto session = targets("--method dt-seed", session_png);
  const auto guard = targets("--method dt-seed --r1-guard", guard_png);
  const auto printed = targets("--method dt-seed --no-r1-guard", printed_png);
  ASSERT_EQ(standard.size(), session.size());
  ASSERT_EQ(standard.size(), printed.size());
  EXPECT_EQ(read_bytes(session_png), read_bytes(guard_png)) << "the default is the guard on";
  int hidden_as_printed = 0;
  for (std::size_t i = 0; i < standard.size(); ++i) {
    const long full = standard[i]["silhouette_pixels"].get<long>();
    if (full == 0 || standard[i]["visible_pixels"].get<long>() != full) continue;
    SCOPED_TRACE("target " + std::to_string(i) + ", wholly visible under standard (" + std::to_string(full) + " pixels)");
    EXPECT_GT(session[i]["visible_pixels"].get<long>(), 0);
    if (printed[i]["visible_pixels"].get<long>() == 0) ++hidden_as_printed;
  }
  EXPECT_GE(hidden_as_printed, 1) << "the article as printed hides a wholly visible target in this scene";
  for (const fs::path& f : {standard_png, session_png, guard_png, printed_png}) fs::remove(f);
}

// The lens method (docs/render.md, "lens"): its passes in the paper's order, and an eraser cone
// through the ABSTRACT cube uncovers targets standard leaves hidden.
TEST(RenderCli, LensRendersItsPassesAndUncoversTargets) {
  const fs::path out = png_path("lens");
  const auto [standard, standard_passes] = visible("standard", out);
  const auto [lens, lens_passes] =
      visible("lens --lens-shape cone --lens-style eraser --lens-radius 20 --lens-length 100", out);
  EXPECT_EQ(lens_passes, nlohmann::json({"lens-back", "lens-front", "lens-behind", "lens-inside", "lens-in-front",
                                         "present"}));
  EXPECT_GT(lens, standard);
  fs::remove(out);
}

// The vdt method (docs/render.md, "vdt"): its passes in the paper's order (section 6.2), and
// targets seen through the nearest distractor where standard leaves them hidden.
TEST(RenderCli, VdtRendersItsPassesAndShowsTargetsThroughDistractors) {
  const fs::path out = png_path("vdt");
  const auto [standard, standard_passes] = visible("standard", out);
  const auto [vdt, vdt_passes] = visible("vdt --vdt-falloff 0.5 --vdt-opaque-alpha 0.6", out);
  EXPECT_EQ(vdt_passes, nlohmann::json({"vdt-nearest", "vdt-second", "vdt-opaque", "vdt-blend", "vdt-foreground",
                                        "present"}));
  EXPECT_GT(vdt, standard);
  fs::remove(out);
}

// The ghosting method (docs/render.md, "ghosting"), added through the technique registry: its
// options come from its keys, its passes run, and targets hidden under standard show through
// the ghosts.
TEST(RenderCli, GhostingRendersItsPassesAndShowsTargetsThroughGhosts) {
  const fs::path out = png_path("ghosting");
  const auto [standard, standard_passes] = visible("standard", out);
  const auto [ghosting, ghosting_passes] = visible("ghosting --ghosting-alpha 0.3 --ghosting-edges false", out);
  EXPECT_EQ(ghosting_passes, nlohmann::json({"ghost-opaque", "ghost-blend", "present"}));
  EXPECT_GT(ghosting, standard);
  fs::remove(out);
}

// --profile: per pass, the median over the timed frames and the mesh draws and triangles it
// submitted. dt-fast's mask and query passes each draw every target once; present draws no mesh.
TEST(RenderCli, ProfileCountsTheDrawsAndTrianglesOfEachPass) {
  const fs::path out = png_path("profile");
  auto passes = [&](const std::string& method) {
    const CliOutcome r = run_dtlab("render --scene abstract --task T1 --seed 7 --width 160 --height 120 --frames 3 "
                                   "--profile --method " + method + " --out '" + out.string() + "'");
    EXPECT_EQ(r.rc, 0) << r.err;
    std::map<std::string, std::pair<long, long>> by_name;  // pass -> (draws, triangles)
    std::istringstream lines(r.out);
    const std::regex row(R"(^\s+\S+ ms\s+(\S+) \(median of (\d+) frames; (\d+) mesh draws, (\d+) triangles\)$)");
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_match(line, m, row)) continue;
      EXPECT_EQ(m[2], "3") << line;
      by_name[m[1]] = {std::stol(m[3]), std::stol(m[4])};
    }
    return by_name;
  };
  const auto standard = passes("standard");
  ASSERT_EQ(standard.size(), 2u);
  EXPECT_GT(standard.at("opaque").first, 0);
  EXPECT_GT(standard.at("opaque").second, standard.at("opaque").first);
  EXPECT_EQ(standard.at("present"), std::make_pair(0L, 0L));
  const auto fast = passes("dt-fast");
  ASSERT_TRUE(fast.count("dt-masks") && fast.count("target-query")) << "passes: " << fast.size();
  EXPECT_GT(fast.at("target-query").first, 0);
  EXPECT_EQ(fast.at("dt-masks"), fast.at("target-query"));
  EXPECT_LT(fast.at("target-query").first, standard.at("opaque").first);
  fs::remove(out);
}

// --occlusion-culling: the JSON says what was culled, and the PNG is the same file as without it.
TEST(RenderCli, OcclusionCullingReportsAndKeepsThePicture) {
  const fs::path on = png_path("culling-on"), off = png_path("culling-off");
  const std::string scene = "render --scene walkthrough --task T3 --seed 1 --method standard --width 160 --height 120 ";
  const CliOutcome a = run_dtlab(scene + "--occlusion-culling --json --out '" + on.string() + "'");
  ASSERT_EQ(a.rc, 0) << a.err;
  const auto j = nlohmann::json::parse(a.out);
  ASSERT_TRUE(j.contains("culling"));
  EXPECT_GT(j["culling"]["objects_culled"].get<int>(), 0);  // the start view faces a wall
  EXPECT_LE(j["culling"]["objects_culled"].get<int>(), j["culling"]["objects_in_view"].get<int>());
  EXPECT_GT(j["culling"]["preprocess_ms"].get<double>(), 0.0);
  const CliOutcome b = run_dtlab(scene + "--json --out '" + off.string() + "'");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_FALSE(nlohmann::json::parse(b.out).contains("culling"));
  EXPECT_EQ(read_bytes(on), read_bytes(off));
  fs::remove(on);
  fs::remove(off);
}

// Screen-door (docs/render.md, "screen-door"): its passes, and it uncovers targets standard leaves
// hidden (the visual model's picture, as dt-seed).
TEST(RenderCli, ScreenDoorRendersItsPassesAndUncoversTargets) {
  const fs::path out = png_path("screen-door");
  const auto [standard, standard_passes] = visible("standard", out);
  const auto [sd, sd_passes] = visible("screen-door --screen-door-mask 16 --screen-door-masks pixel-tree", out);
  ASSERT_GE(sd_passes.size(), 5u);
  EXPECT_EQ(sd_passes[2], "sd-silhouettes");
  EXPECT_EQ(sd_passes[3], "sd-region 1");
  EXPECT_EQ(sd_passes.back(), "present");
  EXPECT_GT(sd, standard);
  fs::remove(out);
}

struct BadCase {
  const char* name;
  std::string args;
  const char* message;  // a part of the error message
};

// ctest lists the case's name, not a byte dump.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class RenderCliBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(RenderCliBad, ExitsTwoWithAMessageAndWritesNothing) {
  const fs::path out = png_path(GetParam().name);
  const CliOutcome r = run_dtlab("render " + GetParam().args + " --out '" + out.string() + "'");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("DtSettings"), std::string::npos) << "names an internal field: " << r.err;
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Forms, RenderCliBad,
    ::testing::Values(
        BadCase{"protocol_and_scene", "--protocol " + kReference + " --index 0 --trial 1 --scene abstract",
                "drop --scene"},
        BadCase{"protocol_and_method", "--protocol " + kReference + " --index 0 --trial 1 --method dt-fast",
                "drop --method"},
        BadCase{"protocol_and_seed", "--protocol " + kReference + " --index 0 --trial 1 --seed 5", "drop --seed"},
        BadCase{"protocol_without_trial", "--protocol " + kReference + " --index 0", "--trial"},
        BadCase{"protocol_without_index", "--protocol " + kReference + " --trial 1", "--index K"},
        BadCase{"trial_past_the_plan", "--protocol " + kReference + " --index 0 --trial 25", "positions 1..24"},
        // Regression: --trial was 0-based while `dtlab plan` positions are 1-based.
        BadCase{"trial_zero", "--protocol " + kReference + " --index 0 --trial 0", "positions 1..24"},
        // Regressions (each used to render a flat or empty image without a word):
        BadCase{"camera_distance_zero", kAbstract + " --camera distance=0", "distance must be"},
        BadCase{"camera_distance_negative", kAbstract + " --camera distance=-5", "distance must be"},
        BadCase{"camera_distance_huge", kAbstract + " --camera distance=1e30", "distance must be"},
        BadCase{"camera_fov_tiny", kAbstract + " --camera fov=1e-9", "fov must be 1..170"},
        BadCase{"camera_pitch_1000", kAbstract + " --camera pitch=1000", "pitch must be -90..90"},
        BadCase{"camera_duplicate_key", kAbstract + " --camera yaw=10,yaw=20", "'yaw' given twice"},
        BadCase{"camera_trailing_comma", kAbstract + " --camera yaw=10,", "trailing comma"},
        BadCase{"camera_walk_key_on_orbit", kAbstract + " --camera x=3", "applies to walk cameras"},
        BadCase{"seed_negative", "--scene abstract --task T1 --seed -1 --method standard", "no sign"},
        // Errors name the option the user wrote, not DtSettings' fields.
        BadCase{"alpha_target_one", kAbstract + " --alpha-target 1", "--alpha-target: must be at least 0 and below 1"},
        BadCase{"gradient_px_huge", kAbstract + " --gradient-px 5000", "--gradient-px: must be 0..4096"},
        // Regression: --mask-res 8192 ran for minutes; a mask finer than the image has no use.
        BadCase{"mask_finer_than_the_image", "--scene abstract --task T1 --seed 1 --method dt-seed --mask-res 8192 --width 200 --height 150",
                "--mask-res: must be at most 200"},
        BadCase{"index_without_protocol", "--scene abstract --task T1 --seed 1 --method standard --index 0",
                "give --protocol"},
        BadCase{"scene_form_without_method", "--scene abstract --task T1 --seed 1", "missing --method"},
        BadCase{"lens_option_without_lens", kAbstract + " --lens-radius 3", "--method lens only"},
        BadCase{"lens_radius_zero", "--scene abstract --task T1 --seed 1 --method lens --lens-radius 0",
                "--lens-radius must be finite and > 0"},
        BadCase{"lens_at_not_a_pixel", "--scene abstract --task T1 --seed 1 --method lens --lens-at 3",
                "--lens-at: expected X,Y"},
        BadCase{"vdt_option_without_vdt", kAbstract + " --vdt-falloff 0.3", "--method vdt only"},
        BadCase{"vdt_falloff_above_one", "--scene abstract --task T1 --seed 1 --method vdt --vdt-falloff 2",
                "--vdt-falloff"},
        BadCase{"protocol_and_lens", "--protocol " + kReference + " --index 0 --trial 1 --lens-shape box",
                "drop --lens-shape"},
        BadCase{"occlusion_culling_on_abstract", kAbstract + " --occlusion-culling", "walkthrough scenes only"},
        BadCase{"screen_door_option_without_screen_door", kAbstract + " --screen-door-mask 16", "--method screen-door only"},
        BadCase{"ghosting_option_without_ghosting", kAbstract + " --ghosting-alpha 0.3", "--method ghosting only"},
        BadCase{"ghosting_alpha_one", "--scene abstract --task T1 --seed 1 --method ghosting --ghosting-alpha 1",
                "--ghosting-alpha: must be 0..0.99"},
        BadCase{"ghosting_edges_not_boolean", "--scene abstract --task T1 --seed 1 --method ghosting --ghosting-edges maybe",
                "--ghosting-edges: expected true or false"},
        BadCase{"screen_door_mask_12", "--scene abstract --task T1 --seed 1 --method screen-door --screen-door-mask 12",
                "--screen-door-mask"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
