// NaN ("not computed", "not defined for these data") and infinity as the
// statistics return them: one definition for every unit of dtlab_stats, which
// a unity build compiles several to a unit (DEVELOPERS.md, "Build time").
#pragma once
#include <limits>

namespace dtlab::stats {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace dtlab::stats
