// generate() and validate(): parameter checks that make generation unable to
// fail (or fail loudly), then dispatch to the ABSTRACT and WALKTHROUGH
// generators. Every error names the parameter ("abstract.max_radius") and
// what was expected; exceptions never leave generate().
#include "study/scene/generate.h"

#include <cmath>
#include <exception>
#include <numbers>
#include <set>
#include <sstream>

#include "study/common/text.h"
#include "study/scene/detail/generators.h"
#include "study/scene/detail/walkthrough_layout.h"
#include "study/scene/hash.h"
#include "study/scene/letters.h"
#include "study/scene/models.h"

namespace dtlab::scene {
namespace {

Error bad(std::string field, std::string message) { return Error{"", 0, 0, std::move(field), std::move(message)}; }

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

int count_low(double ratio, int n) { return static_cast<int>(std::ceil(ratio * n - 1e-9)); }
int count_high(double ratio, int n) { return static_cast<int>(std::floor(ratio * n + 1e-9)); }

// A ratio range [lo, hi] of n objects that contains at least one whole count.
Status check_ratio(const std::string& field, double lo, double hi, int n) {
  if (!(lo >= 0.0 && lo <= hi && hi <= 1.0))
    return bad(field + "_min", "expected 0 <= " + field + "_min <= " + field + "_max <= 1, got [" + num(lo) + ", " +
                                   num(hi) + "]");
  if (count_low(lo, n) > count_high(hi, n))
    return bad(field + "_min", "the range [" + num(lo) + ", " + num(hi) + "] of " + count(n, "object") +
                                   " contains no whole number of objects");
  return {};
}

bool is_fov(float f) { return f > 0.0f && f < 3.1f; }

}  // namespace

std::string_view kind_name(Kind k) { return k == Kind::abstract ? "abstract" : "walkthrough"; }

std::string_view task_name(Task t) {
  switch (t) {
    case Task::T1: return "T1";
    case Task::T2: return "T2";
    case Task::T3: return "T3";
    case Task::T4: return "T4";
  }
  return "?";
}

std::optional<Kind> parse_kind(std::string_view s) {
  if (s == "abstract") return Kind::abstract;
  if (s == "walkthrough") return Kind::walkthrough;
  return std::nullopt;
}

std::optional<Task> parse_task(std::string_view s) {
  for (Task t : {Task::T1, Task::T2, Task::T3, Task::T4})
    if (s == task_name(t)) return t;
  return std::nullopt;
}

bool task_belongs_to(Task t, Kind k) {
  return (t == Task::T1 || t == Task::T2) == (k == Kind::abstract);
}

Status validate(const AbstractParams& p, Task task) {
  if (p.objects < 1 || p.objects > 100000) return bad("abstract.objects", "expected 1..100000, got " + std::to_string(p.objects));
  if (!(p.cube_size > 0.0f && p.cube_size < 1e6f)) return bad("abstract.cube_size", "expected a positive size below 1e6, got " + num(p.cube_size));
  if (!(p.min_radius > 0.0f && p.min_radius <= p.max_radius))
    return bad("abstract.min_radius", "expected 0 < min_radius <= max_radius, got [" + num(p.min_radius) + ", " + num(p.max_radius) + "]");
  if (!(2.0f * p.max_radius < p.cube_size))
    return bad("abstract.max_radius", "an object of radius " + num(p.max_radius) + " does not fit in a cube of " + num(p.cube_size));
  if (p.color_min < 0 || p.color_min > 255) return bad("abstract.color_min", "expected 0..255, got " + std::to_string(p.color_min));
  if (!is_fov(p.fov_y)) return bad("abstract.fov_y", "expected radians in (0, 3.1), got " + num(p.fov_y));
  if (!(p.orbit_margin >= 1.0f && p.orbit_margin < 100.0f)) return bad("abstract.orbit_margin", "expected 1 <= margin < 100, got " + num(p.orbit_margin));

  double r_lo = p.min_radius, r_hi = p.max_radius;
  if (task == Task::T1) {
    if (Status s = check_ratio("abstract.target_ratio", p.target_ratio_min, p.target_ratio_max, p.objects); !s) return s;
  } else if (task == Task::T2) {
    if (p.letters.empty()) return bad("abstract.letters", "expected at least one of C K R X Y");
    int most_lit = 0;
    for (char c : p.letters) {
      const LetterBitmap* l = find_letter(c);
      if (!l) return bad("abstract.letters", std::string("'") + c + "' is not one of C K R X Y");
      most_lit = std::max(most_lit, l->lit());
    }
    if (Status s = check_ratio("abstract.red_distractor_ratio", p.red_distractor_ratio_min, p.red_distractor_ratio_max, p.objects); !s) return s;
    if (most_lit + count_high(p.red_distractor_ratio_max, p.objects) > p.objects)
      return bad("abstract.objects", "too few objects for " + std::to_string(most_lit) + " letter cones and the red distractors");
    const double rc = p.letter_cone_radius;
    if (!(rc > 0.0 && 4.0 * rc < p.cube_size)) return bad("abstract.letter_cone_radius", "expected 0 < radius < cube_size / 4, got " + num(rc));
    // Neighbouring letter cones (upright, same size) are spacing apart; the
    // enclosure test passes when spacing > (chord offset + sqrt(1 + slack - k)) r <= 0.9 r.
    if (!(p.letter_spacing > 0.9 * rc)) return bad("abstract.letter_spacing", "expected spacing > 0.9 * letter_cone_radius, got " + num(p.letter_spacing));
    // The farthest lit cell is sqrt(2^2 + 3^2) cells from the letter's centre (the cube's vertical axis).
    if (!(std::sqrt(13.0) * p.letter_spacing + rc <= 0.5 * p.cube_size))
      return bad("abstract.letter_spacing", "a letter of spacing " + num(p.letter_spacing) + " does not fit in the cube at every rotation");
    r_lo = std::min(r_lo, rc);
    r_hi = std::max(r_hi, rc);
  }
  // Rejection sampling bound (docs/scene.md "Placement"): the centres that
  // conflict with one placed object lie in a ball of radius F; if n - 1 such
  // balls cover at most 3/4 of the cube of admissible centres, every try
  // succeeds with p >= 1/4 whatever was placed before.
  const double F = detail::abstract_conflict_radius(r_lo, r_hi);
  const double free_side = p.cube_size - 2.0 * r_hi;
  const double blocked = (p.objects - 1) * 4.0 / 3.0 * std::numbers::pi * F * F * F;
  if (blocked > 0.75 * free_side * free_side * free_side)
    return bad("abstract.objects", std::to_string(p.objects) + " objects of radius up to " + num(r_hi) +
                                       " are too many for a cube of " + num(p.cube_size) +
                                       " to guarantee placement without enclosure; lower objects or max_radius");
  return {};
}

Status validate(const WalkthroughParams& p, Task task) {
  if (p.grid_width < 1 || p.grid_width > 256) return bad("walkthrough.grid_width", "expected 1..256, got " + std::to_string(p.grid_width));
  if (p.grid_depth < 1 || p.grid_depth > 256) return bad("walkthrough.grid_depth", "expected 1..256, got " + std::to_string(p.grid_depth));
  if (p.room_min < 1 || p.room_min > std::min(p.grid_width, p.grid_depth))
    return bad("walkthrough.room_min", "expected 1 <= room_min <= the grid's sides, got " + std::to_string(p.room_min));
  if (p.room_max < 2 * p.room_min - 1)
    return bad("walkthrough.room_max", "expected room_max >= 2 * room_min - 1 (so every long room can be split), got " + std::to_string(p.room_max));
  if (!(p.cell_size > 0.0f && p.cell_size < 1000.0f)) return bad("walkthrough.cell_size", "expected 0 < cell_size < 1000, got " + num(p.cell_size));
  if (!(p.wall_thickness > 0.0f && p.wall_thickness < 0.25f * p.cell_size))
    return bad("walkthrough.wall_thickness", "expected 0 < thickness < cell_size / 4, got " + num(p.wall_thickness));
  if (!(p.door_width > 0.0f && p.door_width < p.cell_size - 2.0f * p.wall_thickness))
    return bad("walkthrough.door_width", "expected 0 < door_width < cell_size - 2 * wall_thickness, got " + num(p.door_width));
  if (!(p.wall_height > 0.0f)) return bad("walkthrough.wall_height", "expected a positive height, got " + num(p.wall_height));
  if (!(p.door_height > 0.0f && p.door_height < p.wall_height))
    return bad("walkthrough.door_height", "expected 0 < door_height < wall_height, got " + num(p.door_height));
  if (!(p.eye_height > 0.0f && p.eye_height < p.wall_height))
    return bad("walkthrough.eye_height", "expected 0 < eye_height < wall_height, got " + num(p.eye_height));
  if (!is_fov(p.fov_y)) return bad("walkthrough.fov_y", "expected radians in (0, 3.1), got " + num(p.fov_y));
  const int cells = p.grid_width * p.grid_depth;
  if (p.objects < 1 || p.objects > cells - 1)
    return bad("walkthrough.objects", "expected 1..(cells - 1) = " + std::to_string(cells - 1) + " (one object per cell, not the start cell), got " + std::to_string(p.objects));

  const auto kinds = detail::allowed_kinds(p);
  if (kinds.size() < 2) return bad("walkthrough.kinds", "expected at least two kinds (the target kind and others)");
  std::set<std::string> seen;
  for (const auto& k : kinds) {
    const ModelInfo* m = find_model(k);
    if (!m) {
      std::string all;
      for (const ModelInfo& c : model_catalogue()) all += (all.empty() ? "" : " ") + std::string(c.kind);
      return bad("walkthrough.kinds", "unknown kind '" + k + "'; expected one of: " + all);
    }
    if (!seen.insert(k).second) return bad("walkthrough.kinds", "kind '" + k + "' is listed twice");
    if (m->footprint_radius > detail::cell_half_interior(p))
      return bad("walkthrough.cell_size", "a " + k + " (footprint radius " + num(m->footprint_radius) + ") does not fit in a cell of " + num(p.cell_size));
    if (!(m->height < p.wall_height)) return bad("walkthrough.wall_height", "a " + k + " is taller than the walls");
  }
  if (task == Task::T4 && !(p.count_min >= 1 && p.count_min <= p.count_max && p.count_max <= p.objects))
    return bad("walkthrough.count_min", "expected 1 <= count_min <= count_max <= objects, got [" + std::to_string(p.count_min) + ", " + std::to_string(p.count_max) + "]");
  return {};
}

Result<Scene> generate(Kind kind, Task task, std::uint64_t seed, const Params& params) {
  if (!task_belongs_to(task, kind))
    return bad("task", "task " + std::string(task_name(task)) + " belongs to " +
                           std::string(kind_name(kind == Kind::abstract ? Kind::walkthrough : Kind::abstract)) +
                           " scenes, not " + std::string(kind_name(kind)) + " (T1, T2 abstract; T3, T4 walkthrough)");
  try {
    const Status valid = kind == Kind::abstract ? validate(params.abstract, task) : validate(params.walkthrough, task);
    if (!valid) return valid.error();
    Result<Scene> scene = kind == Kind::abstract ? detail::generate_abstract(task, seed, params.abstract)
                                                 : detail::generate_walkthrough(task, seed, params.walkthrough);
    if (scene.ok()) scene->hash = scene_hash(*scene);
    return scene;
  } catch (const std::exception& e) {
    return bad(std::string(kind_name(kind)), std::string("scene generation failed: ") + e.what());
  }
}

}  // namespace dtlab::scene
