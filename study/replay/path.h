// The walked path of WALKTHROUGH trials drawn on the building's floor plan,
// as SVG (for `dtlab replay`, and the report's path figures): rooms and
// walls with their doorways, the start, each trial's recorded eye positions
// as a line, the target's true position and the participant's marked
// answer. Pure: from the scene's floor plan and the recorded poses; no GL.
// Guarantees: the same input gives the same bytes. Never: reads files.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "study/scene/scene.h"
#include "study/store/store.h"

namespace dtlab::replay {

struct WalkedPath {
  std::string label;                    // shown in the legend, e.g. "trial 5 (T3)"
  std::vector<store::CameraPose> poses; // recorded eye positions, in order
  std::optional<glm::vec2> target;      // the target's true floor position (x, z), if the task has one
  std::optional<glm::vec2> answer;      // the marked answer (x, z), if the participant gave one
};

// One SVG of `side` pixels (square) with the plan and every path (distinct colours, a legend).
std::string path_svg(const scene::FloorPlan& plan, glm::vec3 start, const std::vector<WalkedPath>& paths,
                     int side = 640, const std::string& title = "");

// Length of a walked path on the floor (x, z), world units.
double walked_distance(const std::vector<store::CameraPose>& poses);

}  // namespace dtlab::replay
