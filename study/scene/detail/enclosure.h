// The conservative no-enclosure test of the ABSTRACT scenes (docs/scene.md).
// An object is its bounding ball (centre c, radius r; the mesh lies inside)
// plus a chord: two of its own mesh vertices, midpoint m, half-length rho.
// For any point p, one chord end is at distance >= sqrt(|m - p|^2 + rho^2)
// from p (parallelogram law), so if |m_B - c_A|^2 + rho_B^2 > r_A^2 a vertex
// of B lies outside A's ball and A cannot enclose B. The test may reject
// pairs that do not enclose (conservative); it never accepts one that does.
// Pure arithmetic (no libm), so every machine makes the same decisions.
#pragma once
#include <glm/glm.hpp>

namespace dtlab::scene::detail {

struct Footprint3 {
  glm::dvec3 center;   // bounding-ball centre (the object's origin)
  double radius;       // bounding-ball radius
  glm::dvec3 chord_mid;
  double chord_half2;  // rho^2
};

// Relative slack: a vertex must clear the ball by sqrt(1 + kSlack) - 1 (0.05%),
// far above float rounding in the meshes.
inline constexpr double kEnclosureSlack = 1e-3;

// True when the test cannot rule out that `outer` encloses `inner`.
inline bool may_enclose(const Footprint3& outer, const Footprint3& inner) {
  const glm::dvec3 d = inner.chord_mid - outer.center;
  return glm::dot(d, d) + inner.chord_half2 <= outer.radius * outer.radius * (1.0 + kEnclosureSlack);
}

// True when either object may enclose the other: the pair is not allowed.
inline bool enclosure_conflict(const Footprint3& a, const Footprint3& b) {
  return may_enclose(a, b) || may_enclose(b, a);
}

}  // namespace dtlab::scene::detail
