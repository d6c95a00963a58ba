// The WALKTHROUGH model catalogue: pets, vehicles and furniture, each modelled
// procedurally from primitives (nothing loaded from disk), each with its own
// silhouette and main colour so kinds are told apart at a glance.
// Guarantee: every model stands on y = 0, faces +x, and lies inside the
// cylinder of `footprint_radius` about the y axis, below `height` (tested).
// Footprints and heights are declared constants, never measured from the
// meshes, so placement decisions never depend on sin/cos rounding.
#pragma once
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "study/scene/scene.h"

namespace dtlab::scene {

struct ModelInfo {
  std::string_view kind;      // Object::kind, e.g. "dog", "directors_chair"
  std::string_view family;    // "pet", "vehicle" or "furniture"
  std::string_view label;     // human-readable, e.g. "director's chair"
  // The kind's identifying colour (body, paint, upholstery). Not always the largest area: a
  // bird's stand, a bike's tyres or a bed's headboard cover more of its icon (tests/icons).
  glm::vec3 main_color;
  float footprint_radius;     // world units: x^2 + z^2 <= r^2 for every vertex
  float height;               // world units: 0 <= y <= height for every vertex
  Mesh (*build)();            // builds the mesh (named `kind`), vertex colours set
};

std::span<const ModelInfo> model_catalogue();        // every kind, in a fixed order (pets, vehicles, furniture)
const ModelInfo* find_model(std::string_view kind);  // nullptr if no such kind

}  // namespace dtlab::scene
