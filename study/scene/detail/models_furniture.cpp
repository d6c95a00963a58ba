// Furniture: table (wood, four legs), chair (teal, slatted back), sofa
// (purple, arms and cushions), bed (pink blanket, headboard, pillows), floor
// lamp (cream shade on a brass pole), director's chair (lime canvas on
// crossed wooden legs). Life size, in world units (metres).
#include "study/scene/detail/mesh_builder.h"
#include "study/scene/detail/model_builders.h"
#include "study/scene/models.h"

namespace dtlab::scene::detail {
namespace {
const glm::vec3 kDarkWood{0.35f, 0.22f, 0.12f};
const glm::vec3 kWood{0.6f, 0.42f, 0.22f};
const glm::vec3 kLinen{0.96f, 0.96f, 0.94f};
}  // namespace

Mesh build_table() {
  const glm::vec3 wood = find_model("table")->main_color;
  MeshBuilder b("table");
  b.box({0.0f, 0.75f, 0.0f}, {1.6f, 0.06f, 0.9f}, wood);                   // top
  b.box({0.0f, 0.69f, 0.0f}, {1.44f, 0.08f, 0.74f}, kWood);                 // apron
  for (float x : {0.7f, -0.7f})
    for (float z : {0.36f, -0.36f}) b.cylinder({x, 0.0f, z}, {x, 0.72f, z}, 0.045f, kWood);  // legs
  return std::move(b).finish();
}

Mesh build_chair() {
  const glm::vec3 paint = find_model("chair")->main_color;
  MeshBuilder b("chair");
  b.box({0.0f, 0.46f, 0.0f}, {0.5f, 0.06f, 0.5f}, paint);                 // seat
  for (float x : {0.21f, -0.21f})
    for (float z : {0.21f, -0.21f}) b.cylinder({x, 0.0f, z}, {x, 0.43f, z}, 0.025f, paint);  // legs
  for (float z : {0.21f, -0.21f}) b.cylinder({-0.21f, 0.49f, z}, {-0.23f, 1.02f, z}, 0.025f, paint);  // back posts
  b.box({-0.22f, 0.9f, 0.0f}, {0.04f, 0.2f, 0.44f}, paint);               // top slat
  b.box({-0.22f, 0.68f, 0.0f}, {0.04f, 0.08f, 0.44f}, paint);             // lower slat
  return std::move(b).finish();
}

Mesh build_sofa() {
  const glm::vec3 cover = find_model("sofa")->main_color, cushion{0.62f, 0.3f, 0.76f};
  MeshBuilder b("sofa");
  b.box({0.0f, 0.3f, 0.0f}, {2.0f, 0.36f, 0.9f}, cover);                   // base
  b.box({0.0f, 0.7f, -0.35f}, {2.0f, 0.56f, 0.2f}, cover);                 // back
  for (float x : {0.9f, -0.9f}) b.box({x, 0.6f, 0.05f}, {0.2f, 0.3f, 0.8f}, cover);  // arms
  for (float x : {0.9f, -0.9f})
    for (float z : {0.38f, -0.38f}) b.cylinder({x, 0.0f, z}, {x, 0.12f, z}, 0.04f, kDarkWood);  // feet
  for (float x : {-0.54f, 0.0f, 0.54f}) {
    b.box({x, 0.54f, 0.06f}, {0.52f, 0.12f, 0.62f}, cushion);             // seat cushions
    b.box({x, 0.78f, -0.2f}, {0.52f, 0.4f, 0.12f}, cushion);              // back cushions
  }
  return std::move(b).finish();
}

Mesh build_bed() {
  const glm::vec3 blanket = find_model("bed")->main_color, board{0.75f, 0.3f, 0.5f};
  MeshBuilder b("bed");
  b.box({0.0f, 0.25f, 0.0f}, {2.1f, 0.3f, 1.5f}, kWood);                   // frame
  for (float x : {0.98f, -0.98f})
    for (float z : {0.68f, -0.68f}) b.box({x, 0.05f, z}, {0.1f, 0.1f, 0.1f}, kDarkWood);  // feet
  b.box({0.0f, 0.5f, 0.0f}, {2.0f, 0.2f, 1.4f}, kLinen);                   // mattress
  b.box({-0.3f, 0.63f, 0.0f}, {1.42f, 0.08f, 1.46f}, blanket);             // blanket
  b.box({-0.3f, 0.45f, 0.72f}, {1.42f, 0.3f, 0.03f}, blanket);             // blanket hanging over the sides
  b.box({-0.3f, 0.45f, -0.72f}, {1.42f, 0.3f, 0.03f}, blanket);
  for (float z : {0.35f, -0.35f}) b.ellipsoid({0.75f, 0.66f, z}, {0.16f, 0.07f, 0.28f}, kLinen);  // pillows
  b.box({1.03f, 0.55f, 0.0f}, {0.06f, 1.1f, 1.5f}, board);                 // headboard
  return std::move(b).finish();
}

Mesh build_lamp() {
  const glm::vec3 shade = find_model("lamp")->main_color, brass{0.78f, 0.6f, 0.22f};
  MeshBuilder b("lamp");
  b.frustum({0.0f, 0.0f, 0.0f}, {0.0f, 0.04f, 0.0f}, 0.22f, 0.18f, {0.15f, 0.15f, 0.15f}, 24);  // base
  b.cylinder({0.0f, 0.04f, 0.0f}, {0.0f, 1.4f, 0.0f}, 0.02f, brass);      // pole
  b.sphere({0.0f, 1.36f, 0.0f}, 0.06f, {1.0f, 0.95f, 0.5f});              // bulb
  b.frustum({0.0f, 1.3f, 0.0f}, {0.0f, 1.7f, 0.0f}, 0.3f, 0.17f, shade, 28);  // shade
  b.torus({0.0f, 1.3f, 0.0f}, {0, 1, 0}, 0.3f, 0.012f, brass, 28, 6);     // shade rim
  return std::move(b).finish();
}

Mesh build_directors_chair() {
  const glm::vec3 canvas = find_model("directors_chair")->main_color;
  MeshBuilder b("directors_chair");
  for (float z : {0.27f, -0.27f}) {
    b.cylinder({0.25f, 0.02f, z}, {-0.25f, 0.45f, z}, 0.022f, kWood);     // crossed legs
    b.cylinder({-0.25f, 0.02f, z}, {0.25f, 0.45f, z}, 0.022f, kWood);
    for (float x : {0.25f, -0.25f}) b.box({x, 0.015f, z}, {0.08f, 0.03f, 0.05f}, kWood);  // feet
    b.cylinder({0.25f, 0.45f, z}, {0.25f, 0.67f, z}, 0.02f, kWood);       // arm posts
    b.cylinder({-0.25f, 0.45f, z}, {-0.27f, 0.98f, z}, 0.022f, kWood);    // back posts
    b.box({0.0f, 0.68f, z}, {0.58f, 0.035f, 0.06f}, kWood);               // armrests
    b.cylinder({0.25f, 0.45f, z}, {-0.25f, 0.45f, z}, 0.02f, kWood);      // seat rails
  }
  b.box({0.0f, 0.46f, 0.0f}, {0.48f, 0.02f, 0.52f}, canvas);              // canvas seat
  b.box({-0.265f, 0.84f, 0.0f}, {0.02f, 0.24f, 0.56f}, canvas);           // canvas back
  return std::move(b).finish();
}

}  // namespace dtlab::scene::detail
