// The walked path of WALKTHROUGH trials drawn on the building's floor plan,
// as SVG (for `dtlab replay`, and the report's path figures): rooms and
// walls with their doorways, the start, each trial's recorded eye positions
// as a line, the target's true position and the participant's marked
// answer; several trials' plans side by side in one figure (the report's
// path figure of a participant and task). Pure: from the scene's floor plan
// and the recorded poses; no GL.
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

// The walked path of a recorded trial of `scene`: its poses, the T3 target, a marked (position) answer.
WalkedPath walked_path(const scene::Scene& scene, const std::optional<store::Answer>& answer,
                       std::vector<store::CameraPose> poses, std::string label);

// One plan with its paths as SVG elements (no <svg> wrapper), `width` x `height` pixels from (0, 0).
struct PathPanel {
  std::string markup;
  double width = 0, height = 0;
};

// The plan and every path (distinct colours, a legend; the o/x marker key only from 480 px), `side` pixels wide.
PathPanel path_panel(const scene::FloorPlan& plan, glm::vec3 start, const std::vector<WalkedPath>& paths,
                     int side = 640, const std::string& title = "");
// One SVG document of one panel (path_panel's arguments).
std::string path_svg(const scene::FloorPlan& plan, glm::vec3 start, const std::vector<WalkedPath>& paths,
                     int side = 640, const std::string& title = "");
// One SVG document of several panels, `columns` a row (each row as tall as its tallest), under `title`.
std::string panels_svg(const std::vector<PathPanel>& panels, int columns, const std::string& title = "");

// Length of a walked path on the floor (x, z), world units.
double walked_distance(const std::vector<store::CameraPose>& poses);

}  // namespace dtlab::replay
