// Random rotations from the scene stream (SceneRandom, study/common/random.h)
// using only IEEE-754 basic operations and sqrt (correctly rounded
// everywhere), never sin/cos, so that rotations,
// and every decision that depends on them, are identical on every machine.
// Each sampler rejects at most 1000 times (each try succeeds with p >= pi/4)
// and then throws, so it can never loop forever or give up silently.
#pragma once
#include <cmath>
#include <stdexcept>

#include <glm/glm.hpp>

#include "study/common/random.h"

namespace dtlab::scene::detail {

// A point uniform in the open unit disc minus a tiny centre (so it normalizes).
inline glm::dvec2 sample_disc(SceneRandom& rng) {
  for (int i = 0; i < 1000; ++i) {
    const double x = rng.uniform(-1.0, 1.0), y = rng.uniform(-1.0, 1.0);
    const double s = x * x + y * y;
    if (s < 1.0 && s > 1e-12) return {x, y};
  }
  throw std::runtime_error("sample_disc: 1000 rejections in a row (the random source is broken)");
}

// (cos a, sin a) for an angle a uniform in [0, 2 pi).
inline glm::dvec2 sample_direction(SceneRandom& rng) {
  const glm::dvec2 p = sample_disc(rng);
  return p / std::sqrt(p.x * p.x + p.y * p.y);
}

// A unit quaternion (w, x, y, z) uniform on SO(3): Marsaglia (1972), as used
// for random rotations by Shoemake; q = (x1, y1, x2 f, y2 f), f = sqrt((1 - s1) / s2).
inline glm::dvec4 sample_quaternion(SceneRandom& rng) {
  const glm::dvec2 a = sample_disc(rng), b = sample_disc(rng);
  const double s1 = a.x * a.x + a.y * a.y, s2 = b.x * b.x + b.y * b.y;
  const double f = std::sqrt((1.0 - s1) / s2);
  return {a.x, a.y, b.x * f, b.y * f};
}

// The rotation matrix of a unit quaternion (w, x, y, z), column-major.
inline glm::dmat3 quaternion_matrix(const glm::dvec4& q) {
  const double w = q.x, x = q.y, y = q.z, z = q.w;
  glm::dmat3 m;
  m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
  m[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
  m[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
  return m;
}

// Rotation about +y taking +x to (c, 0, -s): the yaw by the angle whose
// cosine and sine are (c, s), column-major.
inline glm::dmat3 yaw_matrix(glm::dvec2 cs) {
  glm::dmat3 m(1.0);
  m[0] = {cs.x, 0.0, -cs.y};
  m[2] = {cs.y, 0.0, cs.x};
  return m;
}

}  // namespace dtlab::scene::detail
