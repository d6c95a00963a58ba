// Geometry rules of the WALKTHROUGH building shared by the generator and
// validate(): which kinds may appear, how much of a cell a model may use,
// and the wall boxes of a floor plan (walls along grid lines, split around
// doorways, a lintel above each doorway). Pure arithmetic, no libm.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/generate.h"

namespace dtlab::scene::detail {

// Gap kept between a model's footprint and the wall faces of its cell.
inline constexpr float kWallClearance = 0.05f;

// Half the side of the square, centred in a cell, that models may occupy:
// cell_size / 2 - wall_thickness / 2 - clearance.
inline double cell_half_interior(const WalkthroughParams& p) {
  return 0.5 * p.cell_size - 0.5 * p.wall_thickness - kWallClearance;
}

// p.kinds, or every catalogue kind when p.kinds is empty.
std::vector<std::string> allowed_kinds(const WalkthroughParams& p);

struct WallBox {
  glm::vec3 lo, hi;  // world-space axis-aligned box
  bool outer;        // on the plan's outline (impenetrable)
  bool lintel;       // the piece above a doorway
};

// Walls of `plan`: every grid edge on the outline or between two rooms, merged
// into straight runs, each run extended by half a thickness at both ends (so
// corners close) and cut at each doorway (door_width wide, centred on the
// edge) with a lintel from door_height to wall_height.
std::vector<WallBox> wall_boxes(const FloorPlan& plan, const WalkthroughParams& p);

}  // namespace dtlab::scene::detail
