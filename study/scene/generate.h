// Scene generation: (kind, task, seed, parameters) -> Scene. The single entry
// point of the scene stage; the protocol stage fills the parameters.
// Guarantees (each tested over 1000 seeds, docs/scene.md lists them all):
// the same inputs give the same Scene and hash on every machine; every
// invariant of the reference study holds for every seed, or generate()
// returns an Error (it never returns a scene that silently breaks one).
// Never: global RNG, std distributions, libm results in placement decisions.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "study/common/error.h"
#include "study/scene/scene.h"

namespace dtlab::scene {

// ABSTRACT (STUDY.md "ABSTRACT scenario"). Defaults are the reference study;
// where the paper gives no number (object sizes, letter spacing) the default
// is ours, chosen as documented in docs/scene.md.
struct AbstractParams {
  int objects = 200;                       // n, letter cones included
  float cube_size = 100.0f;                // edge of the cube, centred on the origin
  float min_radius = 3.0f;                 // object size = bounding-sphere radius, uniform in [min, max]
  float max_radius = 6.0f;
  double target_ratio_min = 0.10;          // T1: target count uniform in [ceil(min n), floor(max n)]
  double target_ratio_max = 0.20;
  int color_min = 51;                      // distractor green and blue components uniform in [color_min, 255] / 255
  std::string letters = "CKRXY";           // T2: the letter is drawn uniformly from these
  float letter_spacing = 12.0f;            // T2: distance between neighbouring cells of the 5 x 7 grid
  float letter_cone_radius = 4.0f;         // T2: bounding radius of the letter cones
  double red_distractor_ratio_min = 0.05;  // T2: red non-cones, count uniform in [ceil(min n), floor(max n)]
  double red_distractor_ratio_max = 0.10;
  float fov_y = 0.785398163f;              // radians (45 degrees); the orbit distance keeps the cube in view
  float orbit_margin = 1.05f;              // orbit distance = margin * (distance at which the cube just fits)
};

// WALKTHROUGH (STUDY.md "WALKTHROUGH scenario").
struct WalkthroughParams {
  int grid_width = 16;                     // cells along x
  int grid_depth = 16;                     // cells along z
  float cell_size = 4.0f;                  // world units per cell
  int room_min = 2;                        // room sides in cells, in [room_min, room_max]
  int room_max = 6;
  float wall_thickness = 0.2f;
  float wall_height = 3.0f;
  float door_width = 1.2f;
  float door_height = 2.2f;
  float eye_height = 1.7f;
  int objects = 50;                        // n
  std::vector<std::string> kinds;          // allowed model kinds; empty = the whole catalogue (models.h)
  int count_min = 3;                       // T4: objects of the counted kind, uniform in [count_min, count_max]
  int count_max = 8;
  float fov_y = 1.047197551f;              // radians (60 degrees)
};

struct Params {
  AbstractParams abstract;
  WalkthroughParams walkthrough;
};

// The scene for one trial. Errors (never exceptions, never a partial scene):
// field "task" when the task does not belong to the kind (T1/T2 ABSTRACT,
// T3/T4 WALKTHROUGH); "abstract.<name>" / "walkthrough.<name>" when a
// parameter is out of range or the parameters cannot guarantee a valid scene.
Result<Scene> generate(Kind kind, Task task, std::uint64_t seed, const Params& params = {});

// The checks generate() runs before generating, for a protocol validator.
Status validate(const AbstractParams& p, Task task);
Status validate(const WalkthroughParams& p, Task task);

std::string_view kind_name(Kind k);               // "abstract", "walkthrough"
std::string_view task_name(Task t);               // "T1" .. "T4"
std::optional<Kind> parse_kind(std::string_view s);  // inverse of kind_name; nullopt otherwise
std::optional<Task> parse_task(std::string_view s);  // inverse of task_name; nullopt otherwise
bool task_belongs_to(Task t, Kind k);             // T1/T2 -> abstract, T3/T4 -> walkthrough

}  // namespace dtlab::scene
