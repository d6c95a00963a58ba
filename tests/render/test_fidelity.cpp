// dt-fast draws dt-seed's picture. At the defaults a session uses (aT 0.3,
// a0 0.1, n = 8 texels of a 128 x 128 mask, outline, passive) on generated
// ABSTRACT and WALKTHROUGH scenes, several seeds each: inside the effect
// region (pixels where some target's exact mask is below 1, where the two
// methods can differ at all) the mean difference from dt-seed is at most 1.5
// levels and at most 2% of the pixels differ by more than 4 levels; and
// dt-seed's and dt-fast's two frame plans (standard-first, effect-first) each
// give the same image. Regression: before the two shared one texel grid, one gradient
// profile and one outline alpha, dt-fast was 9.8-14.1 levels off in the
// effect region, with 64-84% of its pixels off by more than 4.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "study/scene/generate.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

constexpr int kW = 400, kH = 300;

struct Scene {
  scene::Kind kind;
  scene::Task task;
  int seed;
};
void PrintTo(const Scene& s, std::ostream* os) {
  *os << scene::kind_name(s.kind) << " " << scene::task_name(s.task) << " seed " << s.seed;
}

class Fidelity : public ::testing::TestWithParam<Scene> {};

TEST_P(Fidelity, DtFastDrawsDtSeedsPicture) {
  testing::headless_context();
  const Scene& p = GetParam();
  auto s = scene::generate(p.kind, p.task, static_cast<std::uint64_t>(p.seed));
  ASSERT_TRUE(s.ok());
  auto r = Renderer::create(*s);
  ASSERT_TRUE(r.ok());
  FrameSettings settings;
  settings.dt.gradient_px = gradient_px_from_mask_pixels(8.0f, 128, kW, kH);
  settings.timed = true;  // the query's answer known at once: each method's second frame takes the other plan
  const Camera cam = camera_from_start(s->camera, static_cast<float>(kW) / kH);
  settings.method = Method::dt_seed;
  const FrameReport seed_report = must((*r)->render_offscreen(cam, settings, kW, kH));
  const Image seed = must((*r)->read_color());
  const FrameReport seed_again = must((*r)->render_offscreen(cam, settings, kW, kH));
  const ImageDiff seed_plans = must(compare(seed, must((*r)->read_color())));
  EXPECT_EQ(seed_plans.max_abs, 0) << "dt-seed's two frame plans differ: " << seed_plans.pixels_off_pct
                                   << "% of pixels off by > 4";
  settings.method = Method::dt_fast;
  const FrameReport first = must((*r)->render_offscreen(cam, settings, kW, kH));
  const Image fast_first = must((*r)->read_color());
  const FrameReport second = must((*r)->render_offscreen(cam, settings, kW, kH));
  const Image fast_second = must((*r)->read_color());
  const std::vector<std::uint8_t> region = must((*r)->effect_region(cam, settings.dt, kW, kH));
  const ImageDiff d = must(compare_in(fast_first, seed, region));
  std::cout << "effect region " << d.pixels << " px: mean " << d.mae << " levels, " << d.pixels_off_pct
            << "% off by more than 4, max " << d.max_abs << "; whole frame mean " << must(compare(fast_first, seed)).mae
            << "\n";
  RecordProperty("effect_region_mae", std::to_string(d.mae));
  RecordProperty("effect_region_pixels_off_pct", std::to_string(d.pixels_off_pct));
  EXPECT_GT(d.pixels, 0) << "a scene without an effect region tests nothing";
  EXPECT_LE(d.mae, 1.5);
  EXPECT_LE(d.pixels_off_pct, 2.0);
  const ImageDiff plans = must(compare(fast_first, fast_second));
  EXPECT_LE(plans.max_abs, 1) << "the two frame plans differ: " << plans.pixels_off_pct << "% of pixels off by > 4";
  const auto runs = [](const FrameReport& f, const char* pass) {
    const auto v = f.passes_run();
    return std::find(v.begin(), v.end(), pass) != v.end();
  };
  EXPECT_TRUE(runs(seed_report, "dt-clear")) << "some target must be occluded for the test to mean anything";
  EXPECT_TRUE(runs(seed_report, "opaque"));
  EXPECT_FALSE(runs(seed_again, "opaque")) << "the second dt-seed frame must take the effect-first plan";
  EXPECT_TRUE(runs(first, "dt-composite"));
  EXPECT_TRUE(runs(second, "dt-direct"));
}

std::vector<Scene> scenes() {
  std::vector<Scene> out;
  for (int seed : {1, 2, 3, 4, 5}) out.push_back({scene::Kind::abstract, scene::Task::T1, seed});
  for (int seed : {1, 2, 3}) out.push_back({scene::Kind::abstract, scene::Task::T2, seed});
  for (int seed : {1, 2, 3, 4, 5}) out.push_back({scene::Kind::walkthrough, scene::Task::T3, seed});
  for (int seed : {1, 2, 3}) out.push_back({scene::Kind::walkthrough, scene::Task::T4, seed});
  return out;
}
std::string name_of(const ::testing::TestParamInfo<Scene>& info) {
  return std::string(scene::kind_name(info.param.kind)) + "_" + std::string(scene::task_name(info.param.task)) +
         "_seed" + std::to_string(info.param.seed);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Fidelity, ::testing::ValuesIn(scenes()), name_of);

}  // namespace
}  // namespace dtlab::render
