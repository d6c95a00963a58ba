// Vehicles: car (red saloon), bike (blue frame, thin wheels), truck (green cab
// and box body, six wheels), motorbike (black, thick tyres, chrome). Sized at
// about two thirds of life size so they fit a 4 m cell with room to turn.
#include <cmath>
#include <numbers>

#include "study/scene/detail/mesh_builder.h"
#include "study/scene/detail/model_builders.h"
#include "study/scene/models.h"

namespace dtlab::scene::detail {
namespace {
const glm::vec3 kTyre{0.06f, 0.06f, 0.06f};
const glm::vec3 kSilver{0.72f, 0.72f, 0.75f};
const glm::vec3 kGlass{0.55f, 0.75f, 0.92f};
const glm::vec3 kLight{1.0f, 0.95f, 0.7f};

// A wheel whose axle runs along z: tyre cylinder from z0 to z1, hub cap outside.
void wheel(MeshBuilder& b, float x, float y, float z0, float z1, float radius) {
  b.cylinder({x, y, z0}, {x, y, z1}, radius, kTyre, 24);
  const float out = z1 > z0 ? 0.01f : -0.01f;
  b.cylinder({x, y, z1}, {x, y, z1 + out}, radius * 0.5f, kSilver, 16);
}
}  // namespace

Mesh build_car() {
  const glm::vec3 paint = find_model("car")->main_color;
  MeshBuilder b("car");
  b.box({0.0f, 0.5f, 0.0f}, {2.4f, 0.5f, 1.1f}, paint);                 // lower body
  b.box({-0.15f, 0.97f, 0.0f}, {1.25f, 0.44f, 1.0f}, kGlass);            // cabin windows
  b.box({-0.15f, 1.2f, 0.0f}, {1.2f, 0.06f, 1.02f}, paint);              // roof
  for (float x : {0.46f, -0.76f})
    for (float z : {0.505f, -0.505f}) b.box({x, 0.97f, z}, {0.06f, 0.44f, 0.02f}, paint);  // pillars
  for (float x : {0.78f, -0.78f})
    for (float z : {1.0f, -1.0f}) wheel(b, x, 0.3f, 0.43f * z, 0.6f * z, 0.3f);
  for (float z : {0.38f, -0.38f}) {
    b.sphere({1.18f, 0.58f, z}, 0.08f, kLight);                          // headlights
    b.box({-1.2f, 0.58f, z}, {0.03f, 0.1f, 0.2f}, {0.5f, 0.0f, 0.0f});  // tail lights
  }
  for (float x : {1.23f, -1.23f}) b.box({x, 0.32f, 0.0f}, {0.06f, 0.1f, 1.1f}, {0.3f, 0.3f, 0.32f});  // bumpers
  return std::move(b).finish();
}

Mesh build_truck() {
  const glm::vec3 paint = find_model("truck")->main_color;
  MeshBuilder b("truck");
  b.box({0.0f, 0.45f, 0.0f}, {3.0f, 0.2f, 1.0f}, {0.2f, 0.2f, 0.22f});  // chassis
  b.box({1.05f, 1.05f, 0.0f}, {0.85f, 1.1f, 1.2f}, paint);               // cab
  b.box({1.48f, 1.25f, 0.0f}, {0.02f, 0.45f, 1.05f}, kGlass);            // windscreen
  for (float z : {0.605f, -0.605f}) b.box({1.1f, 1.3f, z}, {0.5f, 0.35f, 0.02f}, kGlass);  // side windows
  b.box({1.48f, 0.75f, 0.0f}, {0.03f, 0.3f, 0.8f}, kSilver);            // grille
  for (float z : {0.45f, -0.45f}) b.sphere({1.47f, 0.72f, z}, 0.07f, kLight);  // headlights
  b.box({-0.45f, 1.2f, 0.0f}, {2.0f, 1.3f, 1.25f}, paint);               // box body
  b.box({-1.46f, 1.2f, 0.0f}, {0.03f, 1.2f, 0.04f}, {0.1f, 0.3f, 0.12f});  // rear door seam
  for (float x : {1.05f, -0.2f, -0.95f})
    for (float z : {1.0f, -1.0f}) wheel(b, x, 0.35f, 0.45f * z, 0.66f * z, 0.35f);
  return std::move(b).finish();
}

Mesh build_bike() {
  const glm::vec3 paint = find_model("bike")->main_color;
  MeshBuilder b("bike");
  const float wy = 0.37f, wr = 0.34f;
  for (float cx : {0.55f, -0.55f}) {
    b.torus({cx, wy, 0.0f}, {0, 0, 1}, wr, 0.025f, kTyre, 32, 8);       // tyre
    b.cylinder({cx, wy, -0.04f}, {cx, wy, 0.04f}, 0.03f, kSilver, 10);  // hub
    for (int k = 0; k < 8; ++k) {                                        // spokes
      const float a = static_cast<float>(k) * std::numbers::pi_v<float> / 4.0f;
      b.cylinder({cx, wy, 0.0f}, {cx + (wr - 0.02f) * std::cos(a), wy + (wr - 0.02f) * std::sin(a), 0.0f}, 0.006f,
                 kSilver, 6);
    }
  }
  const glm::vec3 rear{-0.55f, wy, 0.0f}, front{0.55f, wy, 0.0f}, bracket{0.0f, 0.34f, 0.0f};
  const glm::vec3 seat{-0.15f, 0.85f, 0.0f}, head{0.42f, 0.88f, 0.0f}, head_low{0.45f, 0.75f, 0.0f};
  const float tube = 0.026f;
  b.cylinder(rear, bracket, tube, paint);     // chain stay
  b.cylinder(rear, seat, tube, paint);        // seat stay
  b.cylinder(bracket, seat, tube, paint);     // seat tube
  b.cylinder(bracket, head_low, tube, paint); // down tube
  b.cylinder(seat, head, tube, paint);        // top tube
  b.cylinder(head_low, head, tube, paint);    // head tube
  b.cylinder(head_low, front, tube, paint);   // fork
  b.cylinder(head, {0.4f, 1.0f, 0.0f}, 0.02f, kSilver);                          // stem
  b.cylinder({0.4f, 1.0f, -0.28f}, {0.4f, 1.0f, 0.28f}, 0.018f, kSilver);        // handlebar
  for (float z : {0.22f, -0.22f}) b.cylinder({0.4f, 1.0f, z}, {0.4f, 1.0f, z * 1.27f}, 0.024f, kTyre);  // grips
  b.cylinder(seat, {-0.17f, 0.93f, 0.0f}, 0.018f, kSilver);                      // seat post
  b.ellipsoid({-0.17f, 0.95f, 0.0f}, {0.13f, 0.03f, 0.07f}, kTyre);              // saddle
  b.cylinder({0.0f, 0.34f, -0.1f}, {0.0f, 0.34f, 0.1f}, 0.05f, kSilver);         // crank
  for (float z : {0.12f, -0.12f}) b.box({0.0f, 0.34f, z}, {0.1f, 0.02f, 0.06f}, kTyre);  // pedals
  return std::move(b).finish();
}

Mesh build_motorbike() {
  const glm::vec3 paint = find_model("motorbike")->main_color;
  MeshBuilder b("motorbike");
  const float wy = 0.39f;
  for (float cx : {0.7f, -0.7f}) {
    b.torus({cx, wy, 0.0f}, {0, 0, 1}, 0.3f, 0.09f, kTyre, 32, 10);      // fat tyre
    b.cylinder({cx, wy, -0.03f}, {cx, wy, 0.03f}, 0.22f, kSilver, 24);   // rim
  }
  b.box({0.0f, 0.5f, 0.0f}, {0.5f, 0.4f, 0.34f}, kSilver);              // engine
  for (float z : {0.19f, -0.19f}) b.cylinder({0.0f, 0.5f, 0.0f}, {0.0f, 0.5f, z}, 0.12f, {0.5f, 0.5f, 0.52f});  // cylinder heads
  b.ellipsoid({0.15f, 0.88f, 0.0f}, {0.32f, 0.14f, 0.17f}, paint);      // fuel tank
  b.box({-0.35f, 0.86f, 0.0f}, {0.55f, 0.1f, 0.3f}, {0.2f, 0.12f, 0.08f});  // seat
  b.box({-0.62f, 0.76f, 0.0f}, {0.45f, 0.06f, 0.22f}, paint);           // rear fender
  b.cylinder({-0.7f, wy, 0.0f}, {-0.1f, 0.8f, 0.0f}, 0.04f, paint);     // swing arm / frame
  b.cylinder({-0.1f, 0.8f, 0.0f}, {0.45f, 0.98f, 0.0f}, 0.04f, paint);  // top frame
  b.cylinder({0.0f, 0.3f, 0.0f}, {0.45f, 0.98f, 0.0f}, 0.04f, paint);   // down frame
  for (float z : {0.09f, -0.09f}) b.cylinder({0.7f, wy, z}, {0.5f, 1.0f, z}, 0.03f, kSilver);  // fork
  b.cylinder({0.48f, 1.08f, -0.38f}, {0.48f, 1.08f, 0.38f}, 0.02f, kSilver);  // handlebar
  b.cylinder({0.5f, 1.0f, 0.0f}, {0.48f, 1.08f, 0.0f}, 0.03f, kSilver);       // stem
  b.sphere({0.62f, 0.95f, 0.0f}, 0.1f, kLight);                                // headlight
  b.cylinder({0.1f, 0.3f, 0.2f}, {-0.75f, 0.38f, 0.2f}, 0.05f, kSilver);     // exhaust
  return std::move(b).finish();
}

}  // namespace dtlab::scene::detail
