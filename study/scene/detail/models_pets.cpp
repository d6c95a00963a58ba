// Pets: dog (brown, floppy ears, red collar), cat (grey, pointed ears, tail
// up), bird (yellow, on a perch stand), fish (orange, in an open-frame tank).
// Dimensions are world units (metres), chosen a little above life size so a
// pet is still seen across a room.
#include <cmath>

#include "study/scene/detail/mesh_builder.h"
#include "study/scene/detail/model_builders.h"
#include "study/scene/models.h"

namespace dtlab::scene::detail {
namespace {
const glm::vec3 kBlack{0.05f, 0.05f, 0.05f};
const glm::vec3 kWhite{0.95f, 0.95f, 0.95f};

glm::mat4 roll_z(float angle) {  // rotation about +z (tilts the +x axis up for angle > 0)
  glm::mat4 m(1.0f);
  const float c = std::cos(angle), s = std::sin(angle);
  m[0][0] = c;
  m[0][1] = s;
  m[1][0] = -s;
  m[1][1] = c;
  return m;
}
}  // namespace

Mesh build_dog() {
  const glm::vec3 fur = find_model("dog")->main_color, dark{0.33f, 0.19f, 0.08f};
  MeshBuilder b("dog");
  b.ellipsoid({0.0f, 0.55f, 0.0f}, {0.42f, 0.19f, 0.17f}, fur);                 // body
  for (float x : {0.27f, -0.27f})
    for (float z : {0.1f, -0.1f}) b.cylinder({x, 0.0f, z}, {x, 0.5f, z}, 0.06f, fur);  // legs
  for (float x : {0.27f, -0.27f})
    for (float z : {0.1f, -0.1f}) b.ellipsoid({x + 0.03f, 0.035f, z}, {0.08f, 0.035f, 0.05f}, dark);  // paws
  b.cylinder({0.32f, 0.6f, 0.0f}, {0.44f, 0.82f, 0.0f}, 0.09f, fur);            // neck
  b.torus({0.37f, 0.7f, 0.0f}, {0.5f, 0.9f, 0.0f}, 0.095f, 0.022f, {0.85f, 0.1f, 0.1f});  // collar
  b.sphere({0.48f, 0.88f, 0.0f}, 0.15f, fur);                                    // head
  b.ellipsoid({0.63f, 0.84f, 0.0f}, {0.1f, 0.065f, 0.065f}, dark);               // snout
  b.sphere({0.725f, 0.86f, 0.0f}, 0.03f, kBlack);                                // nose
  for (float z : {0.06f, -0.06f}) b.sphere({0.6f, 0.93f, z}, 0.022f, kBlack);    // eyes
  for (float z : {0.14f, -0.14f})
    b.ellipsoid({0.46f, 0.86f, z}, {0.06f, 0.12f, 0.025f}, dark, roll_z(-0.3f));  // floppy ears
  b.cylinder({-0.38f, 0.62f, 0.0f}, {-0.6f, 0.86f, 0.0f}, 0.035f, fur);          // tail
  return std::move(b).finish();
}

Mesh build_cat() {
  const glm::vec3 fur = find_model("cat")->main_color, pale{0.85f, 0.85f, 0.87f};
  MeshBuilder b("cat");
  b.ellipsoid({0.0f, 0.4f, 0.0f}, {0.32f, 0.13f, 0.12f}, fur);                  // body
  for (float x : {0.2f, -0.2f})
    for (float z : {0.07f, -0.07f}) b.cylinder({x, 0.0f, z}, {x, 0.36f, z}, 0.04f, fur);  // legs
  b.ellipsoid({0.22f, 0.4f, 0.0f}, {0.1f, 0.1f, 0.1f}, pale);                   // chest
  b.sphere({0.38f, 0.6f, 0.0f}, 0.12f, fur);                                     // head
  for (float z : {0.065f, -0.065f}) {
    b.cone({0.37f, 0.66f, z}, {0.38f, 0.83f, z * 1.4f}, 0.05f, fur);            // pointed ears
    b.sphere({0.48f, 0.63f, z * 0.75f}, 0.025f, {0.3f, 0.8f, 0.2f});             // green eyes
  }
  b.sphere({0.5f, 0.58f, 0.0f}, 0.018f, {0.95f, 0.5f, 0.6f});                    // nose
  // Tail curling up behind: a chain of short cylinders.
  const glm::vec3 tail[] = {{-0.3f, 0.44f, 0.0f}, {-0.42f, 0.52f, 0.0f}, {-0.47f, 0.66f, 0.0f},
                            {-0.45f, 0.8f, 0.0f}, {-0.38f, 0.88f, 0.0f}};
  for (int i = 0; i + 1 < 5; ++i) {
    b.cylinder(tail[i], tail[i + 1], 0.03f, fur);
    b.sphere(tail[i + 1], 0.03f, fur);
  }
  return std::move(b).finish();
}

Mesh build_bird() {
  const glm::vec3 feather = find_model("bird")->main_color, wing{0.85f, 0.65f, 0.05f};
  const glm::vec3 metal{0.35f, 0.35f, 0.38f};
  MeshBuilder b("bird");
  b.frustum({0.0f, 0.0f, 0.0f}, {0.0f, 0.05f, 0.0f}, 0.28f, 0.25f, metal);       // stand base
  b.cylinder({0.0f, 0.05f, 0.0f}, {0.0f, 1.15f, 0.0f}, 0.025f, metal);           // pole
  b.cylinder({0.0f, 1.15f, -0.22f}, {0.0f, 1.15f, 0.22f}, 0.02f, {0.5f, 0.35f, 0.2f});  // perch bar
  b.ellipsoid({0.0f, 1.33f, 0.0f}, {0.17f, 0.12f, 0.11f}, feather, roll_z(0.5f));  // body
  b.sphere({0.13f, 1.47f, 0.0f}, 0.085f, feather);                               // head
  b.cone({0.19f, 1.47f, 0.0f}, {0.3f, 1.45f, 0.0f}, 0.035f, {1.0f, 0.5f, 0.05f});  // beak
  for (float z : {0.05f, -0.05f}) b.sphere({0.19f, 1.5f, z}, 0.017f, kBlack);   // eyes
  for (float z : {0.1f, -0.1f})
    b.ellipsoid({-0.02f, 1.33f, z}, {0.15f, 0.07f, 0.02f}, wing, roll_z(0.45f));  // wings
  b.fin({-0.12f, 1.25f, 0.0f}, {-0.32f, 1.12f, 0.0f}, 0.07f, {0, 1, 0}, 0.025f, wing);  // tail
  for (float z : {0.04f, -0.04f}) b.cylinder({0.0f, 1.16f, z}, {0.01f, 1.23f, z}, 0.012f, {1.0f, 0.5f, 0.05f});  // legs
  return std::move(b).finish();
}

Mesh build_fish() {
  const glm::vec3 scales = find_model("fish")->main_color;
  const glm::vec3 frame{0.1f, 0.1f, 0.12f}, sand{0.85f, 0.8f, 0.62f}, weed{0.1f, 0.6f, 0.15f};
  MeshBuilder b("fish");
  // Open tank frame: the 12 edges of a 1.0 x 0.6 x 0.5 cuboid on four legs.
  const float x = 0.49f, z = 0.24f, y0 = 0.7f, y1 = 1.3f, t = 0.02f;
  for (float sx : {x, -x})
    for (float sz : {z, -z}) {
      b.cylinder({sx, 0.0f, sz}, {sx, y0, sz}, 0.02f, frame, 10);  // legs
      b.box({sx, 0.5f * (y0 + y1), sz}, {t, y1 - y0, t}, frame);
    }
  for (float y : {y0, y1}) {
    for (float sz : {z, -z}) b.box({0.0f, y, sz}, {2 * x + t, t, t}, frame);
    for (float sx : {x, -x}) b.box({sx, y, 0.0f}, {t, t, 2 * z + t}, frame);
  }
  b.box({0.0f, y0 + 0.02f, 0.0f}, {0.96f, 0.03f, 0.46f}, sand);                 // sand
  for (float px : {-0.32f, 0.34f})
    b.cone({px, y0 + 0.03f, -0.12f}, {px + 0.02f, 1.12f, -0.14f}, 0.05f, weed);  // plants
  // Two goldfish: body, tail fan, dorsal fin, eyes.
  auto goldfish = [&](glm::vec3 c, float s, float dir) {
    b.ellipsoid(c, glm::vec3(0.32f, 0.19f, 0.09f) * s, scales);
    b.fin(c + glm::vec3(-0.26f * dir, 0.0f, 0.0f) * s, c + glm::vec3(-0.5f * dir, 0.0f, 0.0f) * s, 0.17f * s,
          {0, 0, 1}, 0.03f * s, scales);
    b.fin(c + glm::vec3(0.04f * dir, 0.15f, 0.0f) * s, c + glm::vec3(-0.1f * dir, 0.28f, 0.0f) * s, 0.11f * s,
          {0, 0, 1}, 0.02f * s, scales);
    for (float ez : {0.07f, -0.07f}) {
      b.sphere(c + glm::vec3(0.22f * dir, 0.04f, ez) * s, 0.03f * s, kWhite);
      b.sphere(c + glm::vec3(0.24f * dir, 0.04f, ez * 1.1f) * s, 0.016f * s, kBlack);
    }
  };
  goldfish({0.06f, 1.0f, 0.04f}, 1.0f, 1.0f);
  goldfish({-0.22f, 0.86f, -0.08f}, 0.55f, -1.0f);
  return std::move(b).finish();
}

}  // namespace dtlab::scene::detail
