// The WALKTHROUGH model catalogue: at least 12 kinds in three families, each
// a valid mesh standing on the floor inside its declared footprint and height
// (placement relies on those constants), its main colour really used, and
// main colours far enough apart to tell kinds apart at a glance.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "study/scene/models.h"
#include "tests/scene/mesh_checks.h"

namespace dtlab::scene {

void PrintTo(const ModelInfo& m, std::ostream* os) { *os << m.kind; }  // readable ctest names

namespace {

TEST(Models, TwelveOrMoreKindsInThreeFamilies) {
  const auto all = model_catalogue();
  EXPECT_GE(all.size(), 12u);
  std::map<std::string, int> per_family;
  std::set<std::string> kinds;
  for (const ModelInfo& m : all) {
    ++per_family[std::string(m.family)];
    EXPECT_TRUE(kinds.insert(std::string(m.kind)).second) << "duplicate kind " << m.kind;
    EXPECT_EQ(find_model(m.kind), &m);
  }
  EXPECT_EQ(per_family.size(), 3u);
  for (const char* f : {"pet", "vehicle", "furniture"}) EXPECT_GE(per_family[f], 4) << f;
  for (const char* k : {"dog", "cat", "bird", "fish", "car", "bike", "truck", "motorbike", "table", "chair", "sofa",
                        "bed", "lamp", "directors_chair"})
    EXPECT_NE(find_model(k), nullptr) << k;
  EXPECT_EQ(find_model("unicorn"), nullptr);
}

class Model : public ::testing::TestWithParam<ModelInfo> {};

TEST_P(Model, StandsInsideItsDeclaredFootprint) {
  const ModelInfo& info = GetParam();
  const Mesh m = info.build();
  EXPECT_EQ(m.name, info.kind);
  EXPECT_TRUE(testing::valid_mesh(m));
  float lowest = 1e9f;
  for (const Vertex& v : m.vertices) {
    const float r = std::sqrt(v.position.x * v.position.x + v.position.z * v.position.z);
    EXPECT_LE(r, info.footprint_radius) << info.kind << " vertex outside the footprint";
    EXPECT_LE(v.position.y, info.height) << info.kind << " vertex above the declared height";
    lowest = std::min(lowest, v.position.y);
  }
  EXPECT_GE(lowest, -1e-4f) << info.kind << " sinks into the floor";
  EXPECT_LE(lowest, 0.02f) << info.kind << " floats above the floor";
  EXPECT_GE(m.triangle_count(), 200u) << info.kind << " is too coarse to look like what it is";
}

// At least 15% of the surface area is the main colour: the colour that
// identifies the kind is really on the model, not just in the catalogue.
TEST_P(Model, MainColourCoversTheModel) {
  const ModelInfo& info = GetParam();
  const Mesh m = info.build();
  double total = 0.0, main = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const Vertex &a = m.vertices[m.indices[t]], &b = m.vertices[m.indices[t + 1]], &c = m.vertices[m.indices[t + 2]];
    const double area = 0.5 * glm::length(glm::cross(b.position - a.position, c.position - a.position));
    total += area;
    if (glm::length(a.color - info.main_color) < 1e-3f) main += area;
  }
  EXPECT_GE(main / total, 0.15) << info.kind;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, Model, ::testing::ValuesIn(model_catalogue().begin(), model_catalogue().end()),
                         [](const auto& info) { return std::string(info.param.kind); });

TEST(Models, MainColoursAreFarApart) {
  const auto all = model_catalogue();
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j)
      EXPECT_GE(glm::length(all[i].main_color - all[j].main_color), 0.2f) << all[i].kind << " vs " << all[j].kind;
}

TEST(Models, BuildingIsDeterministic) {
  for (const ModelInfo& info : model_catalogue()) {
    const Mesh a = info.build(), b = info.build();
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_EQ(a.indices, b.indices);
    for (std::size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i].position, b.vertices[i].position);
  }
}

}  // namespace
}  // namespace dtlab::scene
