// ABSTRACT invariants over 1000 seeds per task (STUDY.md VI.4-VI.5), each
// checked independently of the generator's own bookkeeping: objects inside
// the cube, no object enclosing another (witnessed by a mesh vertex outside
// the other's bounding ball), target ratio and colours, the T2 letter found
// again from the red cones' positions, and the orbit camera framing the cube.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "study/scene/generate.h"
#include "study/scene/letters.h"
#include "tests/scene/mesh_checks.h"

namespace dtlab::scene {
namespace {

using testing::world;

constexpr int kSeeds = 1000;

bool is_red(glm::vec3 c) { return c == glm::vec3(1.0f, 0.0f, 0.0f); }

// Each object's mesh, in world space, with its bounding ball (centre = the
// transform's translation, radius = the transform's scale, the primitives
// lying in the unit ball: test_primitives.cpp).
struct WorldObject {
  std::vector<glm::vec3> vertices;
  glm::vec3 center;
  float radius;
};

std::vector<WorldObject> world_objects(const Scene& s) {
  std::vector<WorldObject> out;
  for (const Object& o : s.objects) {
    WorldObject w;
    for (const Vertex& v : s.meshes[o.mesh].vertices) w.vertices.push_back(world(o, v));
    w.center = glm::vec3(o.transform[3]);
    w.radius = glm::length(glm::vec3(o.transform[0]));
    out.push_back(std::move(w));
  }
  return out;
}

// A vertex of `inner` lies outside `outer`'s bounding ball, so `outer` cannot enclose `inner`.
bool witnessed_not_enclosed(const WorldObject& outer, const WorldObject& inner) {
  const float r2 = outer.radius * outer.radius * (1.0f + 1e-5f);
  for (const glm::vec3& v : inner.vertices) {
    const glm::vec3 d = v - outer.center;
    if (glm::dot(d, d) > r2) return true;
  }
  return false;
}

void check_common(const Scene& s, const AbstractParams& p, std::uint64_t seed) {
  const bool letter_task = s.task == Task::T2;
  SCOPED_TRACE("seed " + std::to_string(seed));
  ASSERT_EQ(s.objects.size(), static_cast<std::size_t>(p.objects));
  ASSERT_EQ(s.meshes.size(), 4u);
  const float half = 0.5f * p.cube_size;
  std::set<std::uint32_t> ids;
  for (const Object& o : s.objects) {
    EXPECT_TRUE(ids.insert(o.id).second);
    EXPECT_GE(o.id, 1u);
    EXPECT_EQ(o.kind, s.meshes[o.mesh].name);
    EXPECT_EQ(o.group, o.id) << "ABSTRACT objects are one group each";
    EXPECT_FALSE(o.impenetrable);
    const float scale = glm::length(glm::vec3(o.transform[0]));
    for (const Vertex& v : s.meshes[o.mesh].vertices) {
      const glm::vec3 w = world(o, v);
      EXPECT_LE(std::max({std::abs(w.x), std::abs(w.y), std::abs(w.z)}), half + 1e-3f) << "object " << o.id << " leaves the cube";
    }
    // Colours: red objects are pure red; others have no red and green/blue in range.
    if (!is_red(o.color)) {
      EXPECT_EQ(o.color.r, 0.0f);
      EXPECT_GE(o.color.g, p.color_min / 255.0f - 1e-6f);
      EXPECT_GE(o.color.b, p.color_min / 255.0f - 1e-6f);
      EXPECT_FALSE(o.target) << "a distractor of another colour is flagged target";
    }
    if (!(letter_task && o.kind == "cone" && is_red(o.color))) {  // letter cones have their own size
      EXPECT_GE(scale, p.min_radius - 1e-4f);
      EXPECT_LE(scale, p.max_radius + 1e-4f);
    }
  }
  const auto objs = world_objects(s);
  for (std::size_t i = 0; i < objs.size(); ++i)
    for (std::size_t j = 0; j < objs.size(); ++j)
      if (i != j) {
        ASSERT_TRUE(witnessed_not_enclosed(objs[i], objs[j])) << "object " << i + 1 << " may enclose " << j + 1;
      }
  EXPECT_EQ(s.bounds_min, glm::vec3(-half));
  EXPECT_EQ(s.bounds_max, glm::vec3(half));
  EXPECT_EQ(s.camera.mode, CameraStart::Mode::orbit);
  EXPECT_FALSE(s.plan.has_value());
  EXPECT_EQ(s.hash.size(), 64u);
}

TEST(Abstract, T1InvariantsHoldForEverySeed) {
  const Params params;
  const AbstractParams& p = params.abstract;
  std::map<std::string, int> kinds;
  int min_targets = 1 << 30, max_targets = 0;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const auto r = generate(Kind::abstract, Task::T1, seed * 7919 + 1, params);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.error().to_string();
    const Scene& s = *r;
    check_common(s, p, seed);
    int red = 0, targets = 0;
    for (const Object& o : s.objects) {
      red += is_red(o.color);
      targets += o.target;
      EXPECT_EQ(o.target, is_red(o.color)) << "T1: targets are exactly the red objects";
      ++kinds[o.kind];
    }
    EXPECT_EQ(s.answer.task, Task::T1);
    EXPECT_EQ(s.answer.count, targets);
    EXPECT_EQ(red, targets);
    EXPECT_GE(targets, 20);  // 10% .. 20% of 200
    EXPECT_LE(targets, 40);
    min_targets = std::min(min_targets, targets);
    max_targets = std::max(max_targets, targets);
    const std::size_t tris = testing::scene_triangles(s);
    EXPECT_GE(tris, 10000u);  // the paper's ABSTRACT scenes: 13k polygons
    EXPECT_LE(tris, 20000u);
  }
  EXPECT_EQ(min_targets, 20) << "the whole ratio range is used";
  EXPECT_EQ(max_targets, 40);
  EXPECT_EQ(kinds.size(), 4u);
  for (const auto& [kind, n] : kinds) EXPECT_GT(n, kSeeds * 200 / 4 * 9 / 10) << kind << " is rare";
}

// Finds a rotation about +y and a translation mapping the letter's lit cells
// (x = (c - 2) s, z = (r - 3) s) onto `points` one to one; no reflection.
bool matches_letter(const std::vector<glm::vec2>& points, const LetterBitmap& letter, float spacing) {
  std::vector<glm::vec2> cells;
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 5; ++c)
      if (letter.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] == '#')
        cells.push_back({static_cast<float>(c - 2) * spacing, static_cast<float>(r - 3) * spacing});
  if (cells.size() != points.size()) return false;
  auto centroid = [](const std::vector<glm::vec2>& v) {
    glm::vec2 c(0.0f);
    for (auto p : v) c += p;
    return c / static_cast<float>(v.size());
  };
  const glm::vec2 cp = centroid(points), cc = centroid(cells);
  // Try each cell as the image of points[k] for the point farthest from the centroid.
  std::size_t far = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (glm::length(points[i] - cp) > glm::length(points[far] - cp)) far = i;
  for (const glm::vec2& target : cells) {
    const glm::vec2 a = points[far] - cp, b = target - cc;
    if (std::abs(glm::length(a) - glm::length(b)) > 1e-2f) continue;
    // Rotation R (in the x-z plane) with R a = b, as a 2D rotation matrix.
    const float cosv = glm::dot(a, b) / glm::dot(a, a), sinv = (a.x * b.y - a.y * b.x) / glm::dot(a, a);
    bool all = true;
    for (const glm::vec2& p : points) {
      const glm::vec2 d = p - cp, q = cc + glm::vec2(cosv * d.x - sinv * d.y, sinv * d.x + cosv * d.y);
      bool hit = false;
      for (const glm::vec2& c : cells) hit = hit || glm::length(c - q) < 1e-2f;
      all = all && hit;
    }
    if (all) return true;
  }
  return false;
}

TEST(Abstract, LetterMatcherRejectsMirrorsAndOtherLetters) {
  std::vector<glm::vec2> r_cells, r_mirror;
  const LetterBitmap& R = *find_letter('R');
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 5; ++c)
      if (R.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] == '#') {
        r_cells.push_back({(c - 2) * 12.0f + 3.0f, (r - 3) * 12.0f - 1.0f});
        r_mirror.push_back({(2 - c) * 12.0f, (r - 3) * 12.0f});
      }
  EXPECT_TRUE(matches_letter(r_cells, R, 12.0f));
  EXPECT_FALSE(matches_letter(r_mirror, R, 12.0f));
  for (const auto& other : kLetters)
    if (other.letter != 'R') {
      EXPECT_FALSE(matches_letter(r_cells, other, 12.0f)) << other.letter;
    }
}

TEST(Abstract, T2InvariantsHoldForEverySeed) {
  const Params params;
  const AbstractParams& p = params.abstract;
  std::map<char, int> letters;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const auto r = generate(Kind::abstract, Task::T2, seed * 104729 + 3, params);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.error().to_string();
    const Scene& s = *r;
    check_common(s, p, seed);
    EXPECT_EQ(s.answer.task, Task::T2);
    const LetterBitmap* letter = find_letter(s.answer.letter);
    ASSERT_NE(letter, nullptr);
    ++letters[s.answer.letter];
    std::vector<glm::vec2> cones;
    float height = 0.0f;
    int red_others = 0;
    for (const Object& o : s.objects) {
      if (!is_red(o.color)) continue;
      EXPECT_TRUE(o.target) << "T2: every red object is uncovered by dynamic transparency";
      if (o.kind != "cone") {
        ++red_others;
        continue;
      }
      const glm::vec3 c(o.transform[3]);
      if (cones.empty()) height = c.y;
      EXPECT_NEAR(c.y, height, 1e-4f) << "letter cones lie in one horizontal plane";
      EXPECT_NEAR(glm::length(glm::vec3(o.transform[1]) - glm::vec3(0, p.letter_cone_radius, 0)), 0.0f, 1e-4f)
          << "letter cones stand upright";
      cones.push_back({c.x, c.z});
    }
    EXPECT_TRUE(matches_letter(cones, *letter, p.letter_spacing)) << "seed " << seed << ": red cones do not form "
                                                                  << s.answer.letter;
    EXPECT_GE(red_others, 10);  // 5% .. 10% of 200
    EXPECT_LE(red_others, 20);
  }
  EXPECT_EQ(letters.size(), 5u) << "every letter occurs";
}

// For every orbit direction (yaw, pitch sampled densely) the cube's 8 corners
// project inside the frustum. Aspect ratios >= 1 only: the distance is set by
// the vertical field of view, which is the narrower one when width >= height.
TEST(Abstract, OrbitKeepsTheWholeCubeInView) {
  for (float fov_deg : {30.0f, 45.0f, 60.0f, 90.0f}) {
    Params params;
    params.abstract.fov_y = fov_deg * std::numbers::pi_v<float> / 180.0f;
    const auto r = generate(Kind::abstract, Task::T1, 42, params);
    ASSERT_TRUE(r.ok());
    const CameraStart& cam = r->camera;
    for (float aspect : {1.0f, 4.0f / 3.0f, 16.0f / 9.0f}) {
      const glm::mat4 proj = glm::perspective(cam.fov_y, aspect, cam.near_plane, cam.far_plane);
      for (int iy = 0; iy < 72; ++iy) {
        for (int ip = -17; ip <= 17; ++ip) {
          const float yaw = static_cast<float>(iy) * 5.0f * std::numbers::pi_v<float> / 180.0f;
          const float pitch = static_cast<float>(ip) * 5.0f * std::numbers::pi_v<float> / 180.0f;
          const glm::vec3 eye = cam.target + cam.distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                                                      std::cos(pitch) * std::cos(yaw));
          const glm::mat4 view = glm::lookAt(eye, cam.target, glm::vec3(0, 1, 0));
          for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 w((corner & 1) ? r->bounds_max.x : r->bounds_min.x,
                              (corner & 2) ? r->bounds_max.y : r->bounds_min.y,
                              (corner & 4) ? r->bounds_max.z : r->bounds_min.z);
            const glm::vec4 clip = proj * view * glm::vec4(w, 1.0f);
            ASSERT_GT(clip.w, 0.0f);
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            ASSERT_LE(std::max({std::abs(ndc.x), std::abs(ndc.y), std::abs(ndc.z)}), 1.0f)
                << "fov " << fov_deg << " aspect " << aspect << " yaw " << yaw << " pitch " << pitch << " corner " << corner;
          }
        }
      }
    }
  }
}

struct BadParam {
  const char* name;
  void (*edit)(AbstractParams&);
  Task task;
  const char* field;
};

void PrintTo(const BadParam& b, std::ostream* os) { *os << b.name; }  // readable ctest names

class AbstractBadParams : public ::testing::TestWithParam<BadParam> {};

TEST_P(AbstractBadParams, AreReportedWithTheirField) {
  Params params;
  GetParam().edit(params.abstract);
  const auto r = generate(Kind::abstract, GetParam().task, 1, params);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, GetParam().field) << r.error().to_string();
  EXPECT_FALSE(r.error().message.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AbstractBadParams,
    ::testing::Values(
        BadParam{"NoObjects", [](AbstractParams& p) { p.objects = 0; }, Task::T1, "abstract.objects"},
        BadParam{"TooCrowded", [](AbstractParams& p) { p.objects = 2000; }, Task::T1, "abstract.objects"},
        BadParam{"RadiiSwapped", [](AbstractParams& p) { p.min_radius = 7.0f; }, Task::T1, "abstract.min_radius"},
        BadParam{"TooBig", [](AbstractParams& p) { p.max_radius = 60.0f; }, Task::T1, "abstract.max_radius"},
        BadParam{"RatioOutOfRange", [](AbstractParams& p) { p.target_ratio_max = 1.5; }, Task::T1, "abstract.target_ratio_min"},
        BadParam{"NoWholeCount", [](AbstractParams& p) { p.objects = 5; p.target_ratio_min = 0.1; p.target_ratio_max = 0.15; }, Task::T1, "abstract.target_ratio_min"},
        BadParam{"BadLetter", [](AbstractParams& p) { p.letters = "CQ"; }, Task::T2, "abstract.letters"},
        BadParam{"NoLetters", [](AbstractParams& p) { p.letters = ""; }, Task::T2, "abstract.letters"},
        BadParam{"LetterTooWide", [](AbstractParams& p) { p.letter_spacing = 20.0f; }, Task::T2, "abstract.letter_spacing"},
        BadParam{"LetterConesTooClose", [](AbstractParams& p) { p.letter_spacing = 3.0f; }, Task::T2, "abstract.letter_spacing"},
        BadParam{"FovZero", [](AbstractParams& p) { p.fov_y = 0.0f; }, Task::T1, "abstract.fov_y"},
        BadParam{"ColorMin", [](AbstractParams& p) { p.color_min = 300; }, Task::T1, "abstract.color_min"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Abstract, WrongTaskIsAnError) {
  for (Task t : {Task::T3, Task::T4}) {
    const auto r = generate(Kind::abstract, t, 1);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "task");
  }
}

TEST(Abstract, FewerObjectsAndOtherSizesStillHoldTheInvariants) {
  Params params;
  params.abstract.objects = 40;
  params.abstract.cube_size = 50.0f;
  params.abstract.min_radius = 1.0f;
  params.abstract.max_radius = 4.0f;
  params.abstract.letter_spacing = 6.0f;
  params.abstract.letter_cone_radius = 2.0f;
  for (Task task : {Task::T1, Task::T2}) {
    for (std::uint64_t seed = 0; seed < 100; ++seed) {
      const auto r = generate(Kind::abstract, task, seed, params);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      check_common(*r, params.abstract, seed);
    }
  }
}

}  // namespace
}  // namespace dtlab::scene
