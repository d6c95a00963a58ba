// Build functions of the WALKTHROUGH models (one per kind), split by family
// over models_pets.cpp, models_vehicles.cpp and models_furniture.cpp. Each
// returns a mesh named after its kind, in model space (models.h conventions).
#pragma once
#include "study/scene/scene.h"

namespace dtlab::scene::detail {

Mesh build_dog();
Mesh build_cat();
Mesh build_bird();
Mesh build_fish();

Mesh build_car();
Mesh build_bike();
Mesh build_truck();
Mesh build_motorbike();

Mesh build_table();
Mesh build_chair();
Mesh build_sofa();
Mesh build_bed();
Mesh build_lamp();
Mesh build_directors_chair();

}  // namespace dtlab::scene::detail
