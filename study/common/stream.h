// A small deterministic random stream for the session, the simulated
// participants and their questionnaire answers: SplitMix64 (mix64 of a
// counter) with bounded integers by rejection, uniform doubles from 53 bits,
// normals by Box-Muller.
// Guarantees: the same seed gives the same integers on every machine; the
// doubles go through libm (log, cos), so they are the same on every run of
// one build, which is what simulated participants promise. Never: a global
// RNG or std:: distributions (their output differs between libraries).
#pragma once
#include <cmath>
#include <cstdint>

#include "study/common/hash.h"

namespace dtlab {

class Stream {
 public:
  explicit Stream(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() { return dtlab::mix64(state_++ * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL); }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n >= 1, without modulo bias.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n);
    for (;;) {
      const std::uint64_t x = next();
      if (x < limit) return x % n;
    }
  }
  bool chance(double p) { return uniform() < p; }
  // Standard normal (Box-Muller, one value per call).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  double normal(double mean, double sd) { return mean + sd * normal(); }

 private:
  std::uint64_t state_;
};

}  // namespace dtlab
