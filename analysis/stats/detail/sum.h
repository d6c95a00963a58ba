// Compensated summation (Neumaier's variant of Kahan summation) for the sums
// of squares: the error stays near one rounding of the total, independent of
// the number of terms. Header-only, no state beyond the accumulator.
#pragma once
#include <cmath>

namespace dtlab::stats::detail {

class Sum {
 public:
  void add(double x) {  // adds x; NaN and inf propagate as in plain addition
    const double t = s_ + x;
    if (std::fabs(s_) >= std::fabs(x))
      c_ += (s_ - t) + x;
    else
      c_ += (x - t) + s_;
    s_ = t;
  }
  double value() const { return s_ + c_; }

 private:
  double s_ = 0.0, c_ = 0.0;
};

}  // namespace dtlab::stats::detail
