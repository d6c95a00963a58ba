// Guaranteed target visibility (rule R1 of the model): over generated scenes,
// dt-seed and dt-fast with the R1 guard leave no target that is inside the
// view without visible pixels, while standard hides some target completely in
// most scenes; without the guard (the article as printed) a sort error hides
// a target in a few scenes. Uses
// seeds 1..100 (ABSTRACT T1) and 1..20 (WALKTHROUGH T3); the command-line
// check over other seeds is `dtlab render --json` (docs/render.md).
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "study/scene/generate.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

constexpr int kW = 256, kH = 192;

struct Count {
  int scenes = 0;
  int scenes_with_hidden_target = 0;
  std::vector<std::string> failures;  // "seed S: target ID"
};

// Seeds first..last (inclusive).
Count run(scene::Kind kind, scene::Task task, int first, int last, Method method, bool guard = true) {
  testing::headless_context();
  Count c;
  for (int seed = first; seed <= last; ++seed) {
    auto s = scene::generate(kind, task, static_cast<std::uint64_t>(seed));
    EXPECT_TRUE(s.ok());
    if (!s.ok()) continue;
    auto r = Renderer::create(*s);
    EXPECT_TRUE(r.ok());
    if (!r.ok()) continue;
    FrameSettings settings;
    settings.method = method;
    settings.dt.gradient_px = gradient_px_from_mask_pixels(8.0f, 128, kW, kH);
    settings.dt.r1_guard = guard;
    const Camera cam = camera_from_start(s->camera, static_cast<float>(kW) / kH);
    const auto vis = must((*r)->visibility(cam, settings, kW, kH));
    bool hidden = false;
    for (const auto& v : vis) {
      if (v.silhouette_pixels > 0 && v.visible_pixels == 0) {
        hidden = true;
        c.failures.push_back("seed " + std::to_string(seed) + ": target " + std::to_string(v.id));
      }
    }
    ++c.scenes;
    c.scenes_with_hidden_target += hidden;
  }
  return c;
}

std::string first(const std::vector<std::string>& v) { return v.empty() ? "" : v.front(); }

// dt-seed's 100 ABSTRACT scenes are its slowest test: two halves, so ctest -j2 runs them side by side.
TEST(Visibility, DtSeedShowsEveryTargetInViewAbstractSeeds1To50) {
  const Count c = run(scene::Kind::abstract, scene::Task::T1, 1, 50, Method::dt_seed);
  EXPECT_EQ(c.failures.size(), 0u) << first(c.failures);
}
TEST(Visibility, DtSeedShowsEveryTargetInViewAbstractSeeds51To100) {
  const Count c = run(scene::Kind::abstract, scene::Task::T1, 51, 100, Method::dt_seed);
  EXPECT_EQ(c.failures.size(), 0u) << first(c.failures);
}
TEST(Visibility, DtFastShowsEveryTargetInViewAbstract) {
  const Count c = run(scene::Kind::abstract, scene::Task::T1, 1, 100, Method::dt_fast);
  EXPECT_EQ(c.failures.size(), 0u) << first(c.failures);
}
TEST(Visibility, DtSeedShowsEveryTargetInViewWalkthrough) {
  const Count c = run(scene::Kind::walkthrough, scene::Task::T3, 1, 20, Method::dt_seed);
  EXPECT_EQ(c.failures.size(), 0u) << first(c.failures);
}
TEST(Visibility, DtFastShowsEveryTargetInViewWalkthrough) {
  const Count c = run(scene::Kind::walkthrough, scene::Task::T3, 1, 20, Method::dt_fast);
  EXPECT_EQ(c.failures.size(), 0u) << first(c.failures);
}
TEST(Visibility, StandardHidesSomeTargetInMostScenes) {
  const Count a = run(scene::Kind::abstract, scene::Task::T1, 1, 100, Method::standard);
  EXPECT_GT(a.scenes_with_hidden_target * 2, a.scenes) << a.scenes_with_hidden_target << " of " << a.scenes;
  const Count w = run(scene::Kind::walkthrough, scene::Task::T3, 1, 20, Method::standard);
  EXPECT_GT(w.scenes_with_hidden_target * 2, w.scenes) << w.scenes_with_hidden_target << " of " << w.scenes;
  RecordProperty("abstract_scenes_with_a_hidden_target", a.scenes_with_hidden_target);
  RecordProperty("walkthrough_scenes_with_a_hidden_target", w.scenes_with_hidden_target);
  std::cout << "standard hides a target completely in " << a.scenes_with_hidden_target << " of " << a.scenes
            << " ABSTRACT and " << w.scenes_with_hidden_target << " of " << w.scenes << " WALKTHROUGH scenes\n";
}

// Without the guard, the article as printed: a target standing in a farther target's gradient
// fades below the visible share (ABSTRACT seed 3: targets 18, 29, 122, 162 at 256 x 192), and a
// sort error hides a target (WALKTHROUGH seed 11: target 158, drawn after the wall in front of it).
// The guard is off unless asked for.
TEST(Visibility, WithoutTheR1GuardTheArticlesAlgorithmHidesTargets) {
  EXPECT_FALSE(DtSettings{}.r1_guard);
  for (Method m : {Method::dt_seed, Method::dt_fast}) {
    SCOPED_TRACE(std::string(to_string(m)));
    EXPECT_EQ(run(scene::Kind::abstract, scene::Task::T1, 3, 3, m, false).failures,
              (std::vector<std::string>{"seed 3: target 18", "seed 3: target 29", "seed 3: target 122",
                                        "seed 3: target 162"}));
    EXPECT_EQ(run(scene::Kind::walkthrough, scene::Task::T3, 11, 11, m, false).failures,
              (std::vector<std::string>{"seed 11: target 158"}));
  }
}

}  // namespace
}  // namespace dtlab::render
