// Tessellated primitives with smooth normals: the four ABSTRACT shapes and
// the building blocks of the WALKTHROUGH models. Every mesh is an indexed
// triangle list with counter-clockwise front faces and unit normals.
// Guarantee: a primitive's tessellation depends only on its arguments; the
// ABSTRACT shapes lie inside the unit ball about the origin and have two
// mesh vertices (their "chord") that are the basis of the no-enclosure test
// (docs/scene.md). Vertex positions go through sin/cos, so they may differ
// in the last bit between C libraries: never hash them.
#pragma once
#include <array>
#include <string_view>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::scene {

// ---- building blocks (any size) ---------------------------------------------
Mesh sphere_mesh(int slices, int stacks);                 // radius 1 about the origin; poles at +-y
Mesh box_mesh(glm::vec3 half_extents);                    // axis-aligned, centred at the origin, flat faces
// Around the y axis, y in [0, height]; r_top = 0 gives a cone (one apex vertex per slice).
Mesh frustum_mesh(int slices, float r_bottom, float r_top, float height, bool cap_bottom, bool cap_top);
Mesh torus_mesh(int major_segments, int minor_segments, float major_radius, float minor_radius);  // around the y axis, in the xz plane

// ---- the ABSTRACT shapes ------------------------------------------------------
enum class Primitive { sphere, cone, box, torus };
inline constexpr std::array<Primitive, 4> kPrimitives{Primitive::sphere, Primitive::cone, Primitive::box,
                                                      Primitive::torus};

std::string_view primitive_name(Primitive p);  // "sphere", "cone", "box", "torus" (also the Object::kind)

// The shape at the ABSTRACT tessellation (about 13k triangles for 200 objects),
// inside the unit ball about the origin: sphere radius 1; cone apex (0,1,0),
// base radius 0.8 at y = -0.6; cube of half-edge 1/sqrt(3); torus radii 0.7
// and 0.3 around the y axis. Scaled by the object's bounding radius.
Mesh primitive_mesh(Primitive p);

// Two vertices of primitive_mesh(p), as far apart as the shape allows
// (diameter 2 except the cone, sqrt(3.2)). The no-enclosure test uses them.
struct Chord {
  glm::vec3 a, b;
};
Chord primitive_chord(Primitive p);

}  // namespace dtlab::scene
