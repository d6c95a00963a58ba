// The Boost.Math error policy of every distribution call in analysis/stats:
// domain, pole, overflow, evaluation and rounding errors become NaN/inf return
// values (errno) instead of exceptions. Inputs are checked before each call;
// no Boost exception may reach the user. Header-only.
#pragma once
#include <boost/math/policies/policy.hpp>

namespace dtlab::stats::detail {

namespace policies = boost::math::policies;
using Policy = policies::policy<policies::domain_error<policies::errno_on_error>,
                                policies::pole_error<policies::errno_on_error>,
                                policies::overflow_error<policies::errno_on_error>,
                                policies::evaluation_error<policies::errno_on_error>,
                                policies::rounding_error<policies::errno_on_error>>;

}  // namespace dtlab::stats::detail
