// The two generators behind generate() (generate.h). Each assumes its
// parameters passed validate() and returns an Error rather than a scene that
// breaks an invariant; exceptions from the samplers are turned into Errors
// by generate().
#pragma once
#include <cstdint>

#include "study/common/error.h"
#include "study/common/random.h"
#include "study/scene/generate.h"

namespace dtlab::scene::detail {

Result<Scene> generate_abstract(Task task, std::uint64_t seed, const AbstractParams& p);
Result<Scene> generate_walkthrough(Task task, std::uint64_t seed, const WalkthroughParams& p);

// The floor plan alone (rooms and doors), drawn from `rng`; see walkthrough.cpp.
FloorPlan generate_floor_plan(const WalkthroughParams& p, SceneRandom& rng);

// The centre-to-centre radius within which a new ABSTRACT object may
// conflict with a placed one, for any radii in [r_min, r_max] and any
// primitive (bounds the rejection rate; docs/scene.md "Placement").
double abstract_conflict_radius(double r_min, double r_max);

}  // namespace dtlab::scene::detail
