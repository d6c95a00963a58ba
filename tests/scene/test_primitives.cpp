// The ABSTRACT primitives and the building blocks: valid meshes, front faces
// outward, inside the unit ball, chord ends are real vertices (the
// no-enclosure test relies on it), and the triangle budget per shape.
#include <gtest/gtest.h>

#include "study/scene/primitives.h"
#include "tests/scene/mesh_checks.h"

namespace dtlab::scene {
namespace {

using testing::valid_mesh;

TEST(Primitives, BuildingBlocksAreValidMeshes) {
  EXPECT_TRUE(valid_mesh(sphere_mesh(3, 2)));
  EXPECT_TRUE(valid_mesh(sphere_mesh(24, 12)));
  EXPECT_TRUE(valid_mesh(box_mesh({1.0f, 2.0f, 0.5f})));
  EXPECT_TRUE(valid_mesh(frustum_mesh(16, 1.0f, 0.5f, 2.0f, true, true)));
  EXPECT_TRUE(valid_mesh(frustum_mesh(16, 1.0f, 0.0f, 2.0f, true, false)));   // cone
  EXPECT_TRUE(valid_mesh(frustum_mesh(16, 0.0f, 1.0f, 2.0f, false, true)));   // upside-down cone
  EXPECT_TRUE(valid_mesh(torus_mesh(24, 8, 1.0f, 0.25f)));
}

TEST(Primitives, RejectBadArguments) {
  EXPECT_THROW(sphere_mesh(2, 2), std::invalid_argument);
  EXPECT_THROW(box_mesh({0.0f, 1.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(frustum_mesh(8, 0.0f, 0.0f, 1.0f, true, true), std::invalid_argument);
  EXPECT_THROW(torus_mesh(8, 8, 0.2f, 0.3f), std::invalid_argument);
}

// The sphere's faces must point outward: every face's normal points away from the centre.
TEST(Primitives, ConvexShapesFaceOutward) {
  for (Primitive p : {Primitive::sphere, Primitive::box, Primitive::cone}) {
    const Mesh m = primitive_mesh(p);
    glm::vec3 centroid(0.0f);
    for (const Vertex& v : m.vertices) centroid += v.position;
    centroid /= static_cast<float>(m.vertices.size());
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::vec3 a = m.vertices[m.indices[t]].position, b = m.vertices[m.indices[t + 1]].position,
                      c = m.vertices[m.indices[t + 2]].position;
      EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centroid), 0.0f) << m.name << " face " << t / 3;
    }
  }
}

struct ShapeCase {
  Primitive shape;
  const char* name;
  std::size_t triangles;
  float chord_length;
};

void PrintTo(const ShapeCase& c, std::ostream* os) { *os << c.name; }  // readable ctest names

class AbstractShape : public ::testing::TestWithParam<ShapeCase> {};

TEST_P(AbstractShape, ValidInsideUnitBallWithVertexChord) {
  const ShapeCase c = GetParam();
  const Mesh m = primitive_mesh(c.shape);
  EXPECT_EQ(m.name, c.name);
  EXPECT_EQ(primitive_name(c.shape), c.name);
  EXPECT_TRUE(valid_mesh(m));
  EXPECT_EQ(m.triangle_count(), c.triangles);
  float farthest = 0.0f;
  for (const Vertex& v : m.vertices) farthest = std::max(farthest, glm::length(v.position));
  EXPECT_LE(farthest, 1.0f + 1e-5f) << "the bounding ball of radius 1 must hold the mesh";
  EXPECT_GE(farthest, 1.0f - 1e-5f) << "the bounding ball should be tight";
  const Chord chord = primitive_chord(c.shape);
  EXPECT_NEAR(glm::length(chord.a - chord.b), c.chord_length, 1e-5f);
  for (glm::vec3 end : {chord.a, chord.b}) {
    float nearest = 1e9f;
    for (const Vertex& v : m.vertices) nearest = std::min(nearest, glm::length(v.position - end));
    EXPECT_LT(nearest, 1e-6f) << c.name << ": chord end (" << end.x << "," << end.y << "," << end.z << ") is not a vertex";
  }
}

INSTANTIATE_TEST_SUITE_P(All, AbstractShape,
                         ::testing::Values(ShapeCase{Primitive::sphere, "sphere", 120, 2.0f},
                                           ShapeCase{Primitive::cone, "cone", 32, 1.78885438f},
                                           ShapeCase{Primitive::box, "box", 12, 2.0f},
                                           ShapeCase{Primitive::torus, "torus", 120, 2.0f}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace dtlab::scene
