// ABSTRACT scenes (STUDY.md, VI.4-VI.5): n primitives in a cube centred on the
// origin, no object enclosing another (detail/enclosure.h), T1 red targets
// among green-blue distractors, T2 a letter of red cones among red
// distractors of other shapes. Placement is rejection sampling whose success
// rate is bounded below by validate() (>= 1/4 per try, so 4096 tries fail
// with probability < 1e-500); if it ever failed, the scene is an Error.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "study/scene/detail/enclosure.h"
#include "study/scene/detail/generators.h"
#include "study/common/random.h"
#include "study/scene/detail/sampling.h"
#include "study/scene/letters.h"
#include "study/scene/primitives.h"

namespace dtlab::scene::detail {
namespace {

constexpr int kMaxPlacementTries = 4096;
constexpr std::uint64_t kStreamAbstract = 0xab57'2ac7ULL;

std::size_t primitive_index(Primitive p) {
  return static_cast<std::size_t>(std::find(kPrimitives.begin(), kPrimitives.end(), p) - kPrimitives.begin());
}

struct Placed {
  Primitive shape;
  double radius;
  glm::dmat3 rotation;
  Footprint3 fp;
};

Footprint3 footprint(Primitive shape, double radius, const glm::dmat3& rotation, glm::dvec3 center) {
  const Chord c = primitive_chord(shape);
  const glm::dvec3 a = center + radius * (rotation * glm::dvec3(c.a));
  const glm::dvec3 b = center + radius * (rotation * glm::dvec3(c.b));
  const glm::dvec3 half = 0.5 * (a - b);
  return {center, radius, 0.5 * (a + b), glm::dot(half, half)};
}

bool conflicts(const Footprint3& fp, const std::vector<Placed>& placed) {
  for (const Placed& p : placed)
    if (enclosure_conflict(fp, p.fp)) return true;
  return false;
}

// Places one object at a uniform position where it conflicts with no placed
// object; false after kMaxPlacementTries tries (validate() makes that
// practically impossible, but it is reported, never ignored).
bool place(SceneRandom& rng, const AbstractParams& p, Primitive shape, double radius, const glm::dmat3& rotation,
           std::vector<Placed>& placed) {
  const double lo = -0.5 * p.cube_size + radius, hi = 0.5 * p.cube_size - radius;
  for (int t = 0; t < kMaxPlacementTries; ++t) {
    // One draw per statement: the order in which function arguments are
    // evaluated is unspecified (g++ goes right to left, clang left to right).
    const double x = rng.uniform(lo, hi);
    const double y = rng.uniform(lo, hi);
    const double z = rng.uniform(lo, hi);
    const glm::dvec3 c(x, y, z);
    const Footprint3 fp = footprint(shape, radius, rotation, c);
    if (!conflicts(fp, placed)) {
      placed.push_back({shape, radius, rotation, fp});
      return true;
    }
  }
  return false;
}

glm::mat4 to_transform(const Placed& o) {
  glm::mat4 m(1.0f);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c][r] = static_cast<float>(o.rotation[c][r] * o.radius);
  m[3] = glm::vec4(glm::vec3(o.fp.center), 1.0f);
  return m;
}

int count_low(double ratio, int n) { return static_cast<int>(std::ceil(ratio * n - 1e-9)); }
int count_high(double ratio, int n) { return static_cast<int>(std::floor(ratio * n + 1e-9)); }

glm::vec3 distractor_color(SceneRandom& rng, const AbstractParams& p) {
  const int g = rng.between(p.color_min, 255), b = rng.between(p.color_min, 255);
  return {0.0f, static_cast<float>(g) / 255.0f, static_cast<float>(b) / 255.0f};
}

Error placement_error(std::size_t index, const AbstractParams& p) {
  return Error{"", 0, 0, "abstract.objects",
               "could not place object " + std::to_string(index + 1) + " of " + std::to_string(p.objects) +
                   " without enclosure after " + std::to_string(kMaxPlacementTries) +
                   " tries; lower abstract.objects or abstract.max_radius"};
}

}  // namespace

double abstract_conflict_radius(double r_min, double r_max) {
  double k = 1.0, e = 0.0;  // min (rho / r)^2 and max |chord midpoint| / r over the primitives
  for (Primitive s : kPrimitives) {
    const Chord c = primitive_chord(s);
    const glm::dvec3 a(c.a), b(c.b), half = 0.5 * (a - b), mid = 0.5 * (a + b);
    k = std::min(k, glm::dot(half, half));
    e = std::max(e, std::sqrt(glm::dot(mid, mid)));
  }
  return std::sqrt(std::max(0.0, r_max * r_max * (1.0 + kEnclosureSlack) - k * r_min * r_min)) + e * r_max;
}

Result<Scene> generate_abstract(Task task, std::uint64_t seed, const AbstractParams& p) {
  SceneRandom rng(seed, kStreamAbstract + static_cast<std::uint64_t>(task));
  Scene scene;
  scene.kind = Kind::abstract;
  scene.task = task;
  scene.seed = seed;
  for (Primitive s : kPrimitives) scene.meshes.push_back(primitive_mesh(s));

  struct Role {
    bool red = false;
    bool target = false;
  };
  std::vector<Placed> placed;
  std::vector<Role> roles;
  placed.reserve(static_cast<std::size_t>(p.objects));
  const auto n = static_cast<std::size_t>(p.objects);

  auto random_shape = [&](bool allow_cone) {
    if (allow_cone) return kPrimitives[rng.below(4)];
    constexpr Primitive others[3] = {Primitive::sphere, Primitive::box, Primitive::torus};
    return others[rng.below(3)];
  };
  auto add_random = [&](Primitive shape, Role role) -> bool {
    const double radius = rng.uniform(p.min_radius, p.max_radius);
    const glm::dmat3 rotation = quaternion_matrix(sample_quaternion(rng));
    if (!place(rng, p, shape, radius, rotation, placed)) return false;
    roles.push_back(role);
    return true;
  };

  if (task == Task::T1) {
    const int targets = rng.between(count_low(p.target_ratio_min, p.objects), count_high(p.target_ratio_max, p.objects));
    std::vector<char> is_target(n, 0);  // a uniform subset of `targets` indices (partial Fisher-Yates)
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    for (std::size_t i = 0; i < static_cast<std::size_t>(targets); ++i) {
      std::swap(order[i], order[i + rng.below(n - i)]);
      is_target[order[i]] = 1;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!add_random(random_shape(true), {is_target[i] != 0, is_target[i] != 0})) return placement_error(i, p);
    scene.answer.task = Task::T1;
    scene.answer.count = targets;
  } else {
    const LetterBitmap& letter = *find_letter(p.letters[rng.below(p.letters.size())]);
    const glm::dmat3 yaw = yaw_matrix(sample_direction(rng));
    const double half_free = 0.5 * p.cube_size - p.letter_cone_radius;
    const double y = rng.uniform(-0.5 * half_free, 0.5 * half_free);
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (letter.rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)] != '#') continue;
        const glm::dvec3 local((col - 2) * static_cast<double>(p.letter_spacing), 0.0,
                               (row - 3) * static_cast<double>(p.letter_spacing));
        glm::dvec3 c = yaw * local;
        c.y = y;
        const Footprint3 fp = footprint(Primitive::cone, p.letter_cone_radius, glm::dmat3(1.0), c);
        if (conflicts(fp, placed))
          return Error{"", 0, 0, "abstract.letter_spacing", "letter cones would enclose each other; raise the spacing"};
        placed.push_back({Primitive::cone, p.letter_cone_radius, glm::dmat3(1.0), fp});  // upright
        roles.push_back({true, true});
      }
    }
    const int lit = letter.lit();
    const int red = rng.between(count_low(p.red_distractor_ratio_min, p.objects),
                                count_high(p.red_distractor_ratio_max, p.objects));
    for (int i = 0; i < red; ++i)
      if (!add_random(random_shape(false), {true, true})) return placement_error(placed.size(), p);
    for (int i = lit + red; i < p.objects; ++i)
      if (!add_random(random_shape(true), {false, false})) return placement_error(placed.size(), p);
    scene.answer.task = Task::T2;
    scene.answer.letter = letter.letter;
  }

  scene.objects.reserve(n);
  for (std::size_t i = 0; i < placed.size(); ++i) {
    Object o;
    o.id = static_cast<std::uint32_t>(i + 1);
    o.kind = std::string(primitive_name(placed[i].shape));
    o.mesh = static_cast<std::uint32_t>(primitive_index(placed[i].shape));
    o.transform = to_transform(placed[i]);
    o.color = roles[i].red ? glm::vec3(1.0f, 0.0f, 0.0f) : distractor_color(rng, p);
    o.target = roles[i].target;
    o.group = o.id;  // one object per group; ABSTRACT has no fixed-order groups
    o.order_in_group = 0;
    scene.objects.push_back(std::move(o));
  }

  const float half = 0.5f * p.cube_size;
  scene.bounds_min = glm::vec3(-half);
  scene.bounds_max = glm::vec3(half);
  CameraStart& cam = scene.camera;
  cam.mode = CameraStart::Mode::orbit;
  cam.target = glm::vec3(0.0f);
  const double cube_radius = 0.5 * std::sqrt(3.0) * p.cube_size;  // the cube's circumscribed sphere
  cam.distance = static_cast<float>(p.orbit_margin * cube_radius / std::sin(0.5 * p.fov_y));
  cam.yaw = 0.0f;
  cam.pitch = 0.3f;
  cam.fov_y = p.fov_y;
  cam.near_plane = static_cast<float>(0.5 * (cam.distance - cube_radius));
  cam.far_plane = static_cast<float>(2.0 * (cam.distance + cube_radius));
  return scene;
}

}  // namespace dtlab::scene::detail
