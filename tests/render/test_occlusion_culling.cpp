// Poon's occlusion culling (thesis ch. 3; docs/render.md, "Occlusion culling"):
// the MOS search on the thesis's Figure 3/4 example, the opacity function on
// its Figure 5 numbers, the sparse depth map against the pixel-wise test, the
// hierarchy's leaves, and the promise that matters: on generated WALKTHROUGH
// scenes (three seeds, views along a route, in doorways, down the longest
// sightline) every method's image with culling on equals, pixel for pixel, the
// image with culling off, while culling does remove objects (dynamic
// transparency in active mode: in passive mode every hidden model is a target
// a mask may reveal, so almost nothing is culled, and the test says so); and
// that its GPU work runs as the frame graph's first stage.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "study/common/random.h"
#include "study/render/detail/occluder_sets.h"
#include "study/render/detail/occlusion_map.h"
#include "study/render/detail/scene_gpu.h"
#include "study/scene/generate.h"
#include "study/scene/route.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using detail::IdSet;
constexpr std::uint32_t A = 0, B = 1, C = 2, D = 3;

// Figure 4 as the text describes it (its pixel counts are not in the text): a first column of
// one-ID slots, A and C; a second column of two-ID slots whose third is BD. Picking A and C leaves
// only BD: the MOSs are ABC and ACD; ABCD is not minimal (Figure 3, right).
const std::vector<IdSet> kFigure4 = {{A, B}, {C}, {B, D}, {A}, {A, C}, {A}, {B, D}};

TEST(MinimumOccluderSet, CombinationTableSortsSlotsBySize) {
  const std::vector<IdSet> expected = {{A}, {C}, {A, B}, {A, C}, {B, D}};
  EXPECT_EQ(detail::combination_table(kFigure4), expected);
}

TEST(MinimumOccluderSet, Figure4GivesAbcAndAcd) {
  const std::vector<double> unit(4, 1.0);
  const std::vector<IdSet> expected = {{A, B, C}, {A, C, D}};  // equal cost: in the order found
  EXPECT_EQ(detail::minimum_occluder_sets(detail::combination_table(kFigure4), unit), expected);
}

TEST(MinimumOccluderSet, CheaperSetFirstAndPruningKeepsOnlyTheCheapest) {
  const std::vector<double> cost = {1.0, 5.0, 1.0, 2.0};  // B dear: ACD (4) before ABC (7)
  const auto table = detail::combination_table(kFigure4);
  const std::vector<IdSet> both = {{A, C, D}, {A, B, C}};
  EXPECT_EQ(detail::minimum_occluder_sets(table, cost), both);
  const std::vector<IdSet> one = {{A, C, D}};
  EXPECT_EQ(detail::minimum_occluder_sets(table, cost, 1), one);
}

TEST(MinimumOccluderSet, RedundantMemberIsDropped) {
  // Slots AB and BC: the search reaches {A, B} (A redundant: B cancels both) and drops it.
  const std::vector<IdSet> expected = {{B}, {A, C}};
  EXPECT_EQ(detail::minimum_occluder_sets(detail::combination_table({{A, B}, {B, C}}), std::vector<double>(3, 1.0)),
            expected);
}

TEST(MinimumOccluderSet, UncoveredPixelMeansVisible) {
  EXPECT_TRUE(detail::combination_table({{A}, {}, {B}}).empty());
  EXPECT_TRUE(detail::minimum_occluder_sets({}, {}).empty());
}

// The thesis's Figure 5 bitmap, rebuilt from its numbers: Op(2,1) = 2, Op(5,1) = 5, Op(2,5) = 9,
// Op(5,5) = 18, and OPF(2,5,1,5) = 2 - 9 - 5 + 18 = 6 of the 12 pixels of (2 < x <= 5, 1 < y <= 5).
detail::OcclusionMap figure5() {
  std::vector<float> depth(25, 1.0f);  // 5 x 5, texel (x, y) 0-based at y * 5 + x
  auto cover = [&](int x, int y) { depth[static_cast<std::size_t>(y * 5 + x)] = 0.5f; };
  for (int x = 0; x < 5; ++x) cover(x, 0);  // the bottom row
  for (int y = 1; y < 5; ++y)
    for (int x = 0; x < 2; ++x)
      if (!(x == 0 && y == 4)) cover(x, y);  // columns 1-2 above it, one hole
  for (int y = 1; y < 3; ++y)
    for (int x = 2; x < 5; ++x) cover(x, y);  // six pixels of the occludee's region
  return detail::make_occlusion_map(depth, 5, 5, 1);
}

TEST(OpacityMap, Figure5OverlapTest) {
  const auto m = figure5();
  EXPECT_EQ(m.op(2, 1), 2);
  EXPECT_EQ(m.op(5, 1), 5);
  EXPECT_EQ(m.op(2, 5), 9);
  EXPECT_EQ(m.op(5, 5), 18);
  EXPECT_EQ(m.opf(2, 5, 1, 5), 6);  // fails the overlap test: 6 < 12
  EXPECT_EQ(m.opf(0, 5, 0, 1), 5);  // the bottom row is covered
}

TEST(OpacityMap, HolesAreNotCovered) {
  std::vector<float> depth(16, 0.5f);
  const auto m = detail::make_occlusion_map(depth, 4, 4, 2, {detail::PixelRect{2, 2, 3, 3}});  // pixel (2,2): texel (1,1)
  EXPECT_EQ(m.opf(0, 4, 0, 4), 15);
  EXPECT_EQ(m.opf(1, 2, 1, 2), 0);
}

TEST(SparseDepthMap, StepsJumpToTheNextPeak) {
  const std::vector<float> row = {0.2f, 0.5f, 0.9f, 0.4f, 0.3f};
  const auto m = detail::make_occlusion_map(row, 5, 1, 1);
  const std::vector<std::uint16_t> steps = {3, 2, 1, 1, 1};  // peaks at x = 2 (0.9), 3 and 4
  EXPECT_EQ(m.steps, steps);
  EXPECT_TRUE(m.behind(0, 0, 5, 1, 0.95f));
  EXPECT_FALSE(m.behind(0, 0, 5, 1, 0.85f));  // the peak 0.9 is not nearer
  EXPECT_TRUE(m.behind(0, 0, 2, 1, 0.6f));    // the run ends at the rectangle: 0.5 decides
  EXPECT_TRUE(m.behind(3, 0, 5, 1, 0.45f));
}

TEST(SparseDepthMap, AgreesWithThePixelWiseTest) {
  Random<SplitMix64> rng(12345);  // data only (study/common/random.h)
  auto next = [&] { return static_cast<float>(rng.below(1000)) / 1000.0f; };
  const int w = 17, h = 9;
  for (int round = 0; round < 200; ++round) {
    std::vector<float> depth(static_cast<std::size_t>(w * h));
    for (auto& d : depth) d = next() < 0.3f ? 0.4f : next();  // plateaus and noise
    const auto m = detail::make_occlusion_map(depth, w, h, 1);
    const int x0 = static_cast<int>(next() * w), x1 = x0 + 1 + static_cast<int>(next() * (w - x0 - 1));
    const int y0 = static_cast<int>(next() * h), y1 = y0 + 1 + static_cast<int>(next() * (h - y0 - 1));
    const float near = next();
    bool all = true;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) all = all && depth[static_cast<std::size_t>(y * w + x)] < near;
    ASSERT_EQ(m.behind(x0, y0, x1, y1, near), all) << "round " << round;
  }
}

scene::Scene walkthrough(std::uint64_t seed) {
  auto s = scene::generate(scene::Kind::walkthrough, scene::Task::T4, seed);
  EXPECT_TRUE(s.ok());
  return s.value();
}

TEST(Hierarchy, LeavesHoldAtMost256TrianglesOrOneObject) {
  testing::headless_context();
  const auto scene = walkthrough(3);
  auto gpu = detail::SceneGpu::create(scene);
  ASSERT_TRUE(gpu.ok());
  const auto& objects = gpu.value()->objects();
  const auto h = detail::build_hierarchy(objects);
  std::vector<int> seen(objects.size(), 0);
  for (const auto& n : h.nodes) {
    if (n.left >= 0) continue;
    long tri = 0;
    for (auto i : n.objects) {
      ++seen[i];
      tri += objects[i].index_count / 3;
    }
    EXPECT_TRUE(n.objects.size() == 1 || tri <= 256) << n.objects.size() << " objects, " << tri << " triangles";
  }
  for (int s : seen) EXPECT_EQ(s, 1);  // every object in exactly one leaf
}

TEST(MinimumOccluderSet, SelectionPicksWallsWithinTheLimit) {
  testing::headless_context();
  const auto scene = walkthrough(1);
  auto gpu = detail::SceneGpu::create(scene);
  ASSERT_TRUE(gpu.ok());
  const auto db = detail::build_occluder_database(scene, gpu.value()->objects());
  ASSERT_EQ(db.cells.size(), static_cast<std::size_t>(16 * 16));
  std::size_t total = 0;
  for (const auto& cell : db.cells) {
    EXPECT_LE(cell.size(), 64u);  // 16 per direction, 4 directions
    for (auto i : cell) EXPECT_EQ(scene.objects[i].kind, "wall");
    total += cell.size();
  }
  EXPECT_GT(total, 0u);
  EXPECT_EQ(&db.nearest({-5.0f, 1.7f, 1e6f}), &db.cells[static_cast<std::size_t>(15 * 16)]);  // clamped to the plan
}

constexpr int kW = 160, kH = 120;

// The views of a seed: every fourth pose of the route, every doorway on it, the longest sightline.
std::vector<scene::Pose> views(const scene::Scene& s) {
  const auto route = scene::walkthrough_route(s);
  std::vector<scene::Pose> out;
  for (std::size_t i = 0; i < route.size(); ++i)
    if (i % 4 == 0 || route[i].doorway) out.push_back(route[i]);
  out.push_back(scene::longest_sightline(s));
  return out;
}

Camera pose_camera(const scene::Scene& s, const scene::Pose& p) {
  return walk_camera(p.position, p.yaw, 0.0f, s.camera.fov_y, static_cast<float>(kW) / kH, s.camera.near_plane,
                     s.camera.far_plane);
}

// A renderer of `s` in the test's headless context.
std::unique_ptr<Renderer> renderer_of(const scene::Scene& s) {
  testing::headless_context();
  auto r = Renderer::create(s);
  EXPECT_TRUE(r.ok());
  return r.ok() ? std::move(r.value()) : nullptr;
}

struct Case {
  Method method;
  const char* name;
  bool active = false;          // dynamic transparency in active mode (a searchlight of 25 pixels)
  bool expect_culling = true;   // passive dt: every hidden model is a target it may reveal
};

class CullingIsInvisible : public ::testing::TestWithParam<Case> {};

TEST_P(CullingIsInvisible, SameImageOnAndOff) {
  long culled = 0, doorways = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto s = walkthrough(seed);
    auto r = renderer_of(s);
    ASSERT_TRUE(r);
    Renderer& renderer = *r;
    FrameSettings f;
    f.method = GetParam().method;
    f.lens = scene_lens(s, kW, kH);
    if (GetParam().active) {
      f.dt.mode = DtMode::active;
      f.dt.searchlight_center = {0.5f * kW, 0.5f * kH};
      f.dt.searchlight_radius = 25.0f;
    }
    for (const scene::Pose& p : views(s)) {
      doorways += p.doorway ? 1 : 0;
      const Camera cam = pose_camera(s, p);
      f.occlusion_culling = false;
      must(renderer.render_offscreen(cam, f, kW, kH));
      const Image off = must(renderer.read_color());
      f.occlusion_culling = true;
      const FrameReport rep = must(renderer.render_offscreen(cam, f, kW, kH));
      const Image on = must(renderer.read_color());
      ASSERT_TRUE(rep.culling.ran);
      culled += rep.culling.objects_culled;
      ASSERT_EQ(on.rgba, off.rgba) << "seed " << seed << " eye (" << p.position.x << ", " << p.position.z
                                   << ") yaw " << p.yaw << ": " << rep.culling.objects_culled << " culled";
    }
  }
  EXPECT_GT(doorways, 0);
  if (GetParam().expect_culling) {
    EXPECT_GT(culled, 0) << "culling removed nothing: the test proves nothing";
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, CullingIsInvisible,
                         ::testing::Values(Case{Method::standard, "standard"}, Case{Method::lens, "lens"},
                                           Case{Method::dt_seed, "dt_seed_active", true},
                                           Case{Method::dt_fast, "dt_fast_active", true},
                                           Case{Method::dt_fast, "dt_fast_passive", false, false},
                                           Case{Method::vdt, "vdt", false, false}),  // walls see-through: none
                         [](const auto& info) { return std::string(info.param.name); });

// `reference` (the exact CPU compositor, slower: the start views only) in active mode.
TEST(OcclusionCulling, ReferenceSameImageAtTheStartViews) {
  long culled = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto s = walkthrough(seed);
    auto r = renderer_of(s);
    ASSERT_TRUE(r);
    FrameSettings f;
    f.method = Method::reference;
    f.dt.mode = DtMode::active;
    f.dt.searchlight_center = {0.5f * kW, 0.5f * kH};
    f.dt.searchlight_radius = 25.0f;
    const Camera cam = camera_from_start(s.camera, static_cast<float>(kW) / kH);
    must(r->render_offscreen(cam, f, kW, kH));
    const Image off = must(r->read_color());
    f.occlusion_culling = true;
    culled += must(r->render_offscreen(cam, f, kW, kH)).culling.objects_culled;
    EXPECT_EQ(must(r->read_color()).rgba, off.rgba) << "seed " << seed;
  }
  EXPECT_GT(culled, 0);
}

// Visible-pixel counts (weight frames with flat colours, what the simulated participant sees)
// are the same with culling on: the weight frames are pictures too.
TEST(OcclusionCulling, VisibilityCountsUnchanged) {
  const auto s = walkthrough(1);
  auto r = renderer_of(s);
  ASSERT_TRUE(r);
  const auto route = scene::walkthrough_route(s);
  for (Method m : {Method::standard, Method::dt_fast}) {
    for (std::size_t i = 0; i < route.size(); i += 5) {
      FrameSettings f;
      f.method = m;
      const auto off = must(r->visibility(pose_camera(s, route[i]), f, kW, kH));
      f.occlusion_culling = true;
      const auto on = must(r->visibility(pose_camera(s, route[i]), f, kW, kH));
      ASSERT_EQ(on.size(), off.size());
      for (std::size_t k = 0; k < on.size(); ++k) {
        EXPECT_EQ(on[k].visible_pixels, off[k].visible_pixels) << to_string(m) << " pose " << i << " target " << k;
        EXPECT_EQ(on[k].silhouette_pixels, off[k].silhouette_pixels);
      }
    }
  }
}

// Regression: the map was sized after it was read on a renderer's first culled frame (argument
// evaluation order), so the first frame culled nothing. The start view of seed 1 faces a wall.
TEST(OcclusionCulling, FirstFrameCullsLikeTheNext) {
  const auto s = walkthrough(1);
  auto r = renderer_of(s);
  ASSERT_TRUE(r);
  FrameSettings f;
  f.occlusion_culling = true;
  const Camera cam = camera_from_start(s.camera, static_cast<float>(kW) / kH);
  const auto first = must(r->render_offscreen(cam, f, kW, kH)).culling;
  const auto second = must(r->render_offscreen(cam, f, kW, kH)).culling;
  EXPECT_GT(first.preprocess_ms, 0.0);
  EXPECT_EQ(second.preprocess_ms, 0.0);  // built once per renderer
  EXPECT_GT(first.objects_culled, 0);
  EXPECT_EQ(first.objects_culled, second.objects_culled);
}

// Renderer::prepare builds the occluder database before the first frame (a session calls it so
// that a trial's first frame is not late by it), and the frames cull as they would without it.
TEST(OcclusionCulling, PrepareBuildsTheDatabaseBeforeTheFirstFrame) {
  const auto s = walkthrough(1);
  auto prepared = renderer_of(s), plain = renderer_of(s);
  ASSERT_TRUE(prepared && plain);
  FrameSettings f;
  EXPECT_EQ(must(prepared->prepare(f)), 0.0) << "culling off: nothing to build";
  f.method = Method::vdt;
  f.occlusion_culling = true;
  EXPECT_EQ(must(prepared->prepare(f)), 0.0) << "vdt culls nothing: nothing to build";
  f.method = Method::standard;
  EXPECT_GT(must(prepared->prepare(f)), 0.0);
  EXPECT_EQ(must(prepared->prepare(f)), 0.0) << "built once per renderer";
  const Camera cam = camera_from_start(s.camera, static_cast<float>(kW) / kH);
  const auto a = must(prepared->render_offscreen(cam, f, kW, kH)).culling;
  const auto b = must(plain->render_offscreen(cam, f, kW, kH)).culling;
  EXPECT_EQ(a.preprocess_ms, 0.0);
  EXPECT_GT(b.preprocess_ms, 0.0);
  EXPECT_GT(a.objects_culled, 0);
  EXPECT_EQ(a.objects_culled, b.objects_culled);
  EXPECT_EQ(a.triangles_culled, b.triangles_culled);
  auto abstract_scene = scene::generate(scene::Kind::abstract, scene::Task::T1, 1);
  ASSERT_TRUE(abstract_scene.ok());
  auto no_plan = renderer_of(abstract_scene.value());
  ASSERT_TRUE(no_plan);
  EXPECT_EQ(must(no_plan->prepare(f)), 0.0) << "no floor plan: nothing to cull with";
}

// Culling's GPU work is part of the frame graph: its three passes run first, in their own stage,
// and show in the pass report (with their draws when profiled) and the Graphviz export; what they
// cull, the method's passes do not draw. Off, or under vdt (which culls nothing), they are absent.
TEST(OcclusionCulling, RunsAsTheFrameGraphsFirstStage) {
  const auto s = walkthrough(1);
  auto r = renderer_of(s);
  ASSERT_TRUE(r);
  const Camera cam = camera_from_start(s.camera, static_cast<float>(kW) / kH);
  FrameSettings f;
  f.profile_passes = true;
  const FrameReport off = must(r->render_offscreen(cam, f, kW, kH));
  f.occlusion_culling = true;
  const FrameReport on = must(r->render_offscreen(cam, f, kW, kH));
  const std::vector<std::string> cull_passes{"cull-occluders", "cull-map", "cull-test"};
  const std::vector<std::string> run = on.passes_run();
  ASSERT_GE(run.size(), 4u);
  EXPECT_EQ(std::vector<std::string>(run.begin(), run.begin() + 3), cull_passes);
  EXPECT_EQ(std::vector<std::string>(run.begin() + 3, run.end()), off.passes_run()) << "the method's passes follow";
  ASSERT_GT(on.culling.objects_culled, 0);
  EXPECT_EQ(on.passes[0].draws, on.culling.occluders) << "cull-occluders draws the occluders in view";
  long method_on = 0, method_off = 0;
  for (std::size_t i = 3; i < on.passes.size(); ++i) method_on += on.passes[i].triangles;
  for (const PassRecord& p : off.passes) method_off += p.triangles;
  EXPECT_LE(method_on, method_off - on.culling.triangles_culled) << "culled triangles are not drawn";
  const std::string dot = r->last_graphviz();
  EXPECT_NE(dot.find("label=\"cull-test\""), std::string::npos);
  EXPECT_NE(dot.find("cluster_stage1"), std::string::npos);
  f.method = Method::vdt;
  for (const std::string& name : must(r->render_offscreen(cam, f, kW, kH)).passes_run())
    EXPECT_EQ(name.rfind("cull-", 0), std::string::npos) << name << ": vdt culls nothing";
}

TEST(OcclusionCulling, HolesOnlyRemoveCoverage) {
  const auto s = walkthrough(2);
  auto r = renderer_of(s);
  ASSERT_TRUE(r);
  FrameSettings f;
  f.occlusion_culling = true;
  long views_with_culling = 0;
  for (const scene::Pose& p : views(s)) {
    const Camera cam = pose_camera(s, p);
    f.method = Method::standard;
    const auto std_rep = must(r->render_offscreen(cam, f, kW, kH)).culling;
    f.method = Method::dt_fast;
    const auto dt_rep = must(r->render_offscreen(cam, f, kW, kH)).culling;
    EXPECT_LE(dt_rep.objects_culled, std_rep.objects_culled);  // holes only remove coverage
    views_with_culling += std_rep.objects_culled > 0 ? 1 : 0;
  }
  EXPECT_GT(views_with_culling, 0);
}

}  // namespace
}  // namespace dtlab::render
