// The scene generators' random source: xoshiro256** (Blackman & Vigna 2018)
// seeded through dtlab::mix64, with our own integer and real conversions.
// Guarantee: the same seed gives the same sequence on every machine; every
// conversion uses only integer arithmetic and IEEE-754 basic operations.
// Never use std::*_distribution, std::random_device or std::rand here: their
// results differ between standard libraries. Never draw twice in one
// expression (f(rng.unit(), rng.unit())): argument order differs by compiler.
#pragma once
#include <cstdint>
#include <stdexcept>

#include "study/common/hash.h"

namespace dtlab::scene::detail {

class Rng {
 public:
  // State from four mix64 outputs of (seed, stream): never all zero in practice
  // (mix64 is a bijection, so at most one of the four words can be zero).
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0) {
    const std::uint64_t base = dtlab::mix64(seed, stream);
    for (int i = 0; i < 4; ++i) s_[i] = dtlab::mix64(base + static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ULL);
  }

  // Next raw 64-bit output of xoshiro256**.
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform integer in [0, n), n > 0, without modulo bias (rejection of the
  // 2^64 mod n lowest raw values).
  std::uint64_t below(std::uint64_t n) {
    if (n == 0) throw std::invalid_argument("Rng::below: n must be positive");
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }

  // Uniform integer in [lo, hi], lo <= hi.
  int between(int lo, int hi) {
    if (lo > hi) throw std::invalid_argument("Rng::between: lo must not exceed hi");
    return lo + static_cast<int>(below(static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo) + 1));
  }

  // Uniform double in [0, 1): the top 53 bits times 2^-53 (exact).
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace dtlab::scene::detail
