// The model catalogue: one row per kind; see models.h. Footprint radius and
// height are declared here (measured once, rounded up) and checked against
// the meshes by tests/scene/test_models.cpp.
#include "study/scene/models.h"

#include <array>

#include "study/scene/detail/model_builders.h"

namespace dtlab::scene {
namespace {

using namespace detail;

const std::array<ModelInfo, 14> kCatalogue{{
    {"dog", "pet", "dog", {0.55f, 0.33f, 0.14f}, 0.80f, 1.05f, build_dog},
    {"cat", "pet", "cat", {0.55f, 0.55f, 0.58f}, 0.65f, 0.95f, build_cat},
    {"bird", "pet", "bird", {0.98f, 0.85f, 0.10f}, 0.40f, 1.60f, build_bird},
    {"fish", "pet", "fish", {1.00f, 0.50f, 0.05f}, 0.60f, 1.35f, build_fish},
    {"car", "vehicle", "car", {0.85f, 0.08f, 0.08f}, 1.45f, 1.25f, build_car},
    {"bike", "vehicle", "bike", {0.10f, 0.30f, 0.95f}, 1.00f, 1.05f, build_bike},
    {"truck", "vehicle", "truck", {0.10f, 0.40f, 0.15f}, 1.70f, 1.90f, build_truck},
    {"motorbike", "vehicle", "motorbike", {0.12f, 0.12f, 0.14f}, 1.20f, 1.15f, build_motorbike},
    {"table", "furniture", "table", {0.80f, 0.62f, 0.38f}, 0.95f, 0.80f, build_table},
    {"chair", "furniture", "chair", {0.05f, 0.62f, 0.66f}, 0.40f, 1.05f, build_chair},
    {"sofa", "furniture", "sofa", {0.48f, 0.16f, 0.62f}, 1.12f, 1.00f, build_sofa},
    {"bed", "furniture", "bed", {0.95f, 0.52f, 0.72f}, 1.35f, 1.12f, build_bed},
    {"lamp", "furniture", "lamp", {0.97f, 0.95f, 0.86f}, 0.32f, 1.72f, build_lamp},
    {"directors_chair", "furniture", "director's chair", {0.58f, 0.85f, 0.12f}, 0.42f, 1.00f,
     build_directors_chair},
}};

}  // namespace

std::span<const ModelInfo> model_catalogue() { return kCatalogue; }

const ModelInfo* find_model(std::string_view kind) {
  for (const ModelInfo& m : kCatalogue)
    if (m.kind == kind) return &m;
  return nullptr;
}

}  // namespace dtlab::scene
