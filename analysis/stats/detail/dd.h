// Double-double arithmetic (a value held as an unevaluated sum hi + lo of two
// doubles, about 106 significant bits) for the few places where a residual
// must be formed from values whose magnitude dwarfs it: data of size 2.5e14
// with residuals of size 1 keep every digit of the residual. Error-free
// transformations TwoSum (Knuth) and TwoProd (fma); Dekker (1971), Hida, Li &
// Bailey (2001). Header-only; never allocates, never throws.
#pragma once
#include <cmath>

namespace dtlab::stats::detail {

struct DD {
  double hi = 0.0, lo = 0.0;

  DD() = default;
  DD(double h) : hi(h) {}  // NOLINT: implicit by design (a double is exact in DD)
  DD(double h, double l) : hi(h), lo(l) {}
  double value() const { return hi + lo; }  // rounded to the nearest double (lo is below hi's last bit)
};

// s + e == a + b exactly, with s = fl(a + b).
inline DD two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

inline DD quick_two_sum(double a, double b) {  // requires |a| >= |b|
  const double s = a + b;
  return {s, b - (s - a)};
}

inline DD operator+(const DD& a, const DD& b) {
  DD s = two_sum(a.hi, b.hi);
  const DD t = two_sum(a.lo, b.lo);
  s.lo += t.hi;
  s = quick_two_sum(s.hi, s.lo);
  s.lo += t.lo;
  return quick_two_sum(s.hi, s.lo);
}

inline DD operator-(const DD& a) { return {-a.hi, -a.lo}; }
inline DD operator-(const DD& a, const DD& b) { return a + (-b); }

// a / n for a count n > 0, correct to about 2^-104 relative.
inline DD divide(const DD& a, double n) {
  const double q1 = a.hi / n;
  const double p = q1 * n;
  const double e = std::fma(q1, n, -p);  // q1 * n == p + e exactly
  const DD r = a - DD(p, e);
  const double q2 = r.value() / n;
  return quick_two_sum(q1, q2);
}

}  // namespace dtlab::stats::detail
