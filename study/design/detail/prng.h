// Internal: a SplitMix64 stream with unbiased bounded integers, the only
// randomness of the design stage. Same sequence on every machine and compiler;
// never touches global state. Not for cryptography.
#pragma once
#include <cstdint>

#include "study/common/hash.h"

namespace dtlab::design::detail {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  // Next 64 random bits: mix64(state), then state += golden gamma (Steele et al. 2014).
  std::uint64_t next() {
    const std::uint64_t r = mix64(state_);
    state_ += 0x9e3779b97f4a7c15ULL;
    return r;
  }

  // Uniform integer in [0, bound), bound >= 1: rejects the low 2^64 mod bound
  // values so every result is equally likely (no modulo bias).
  std::uint64_t below(std::uint64_t bound) {
    const std::uint64_t threshold = (0 - bound) % bound;  // 2^64 mod bound
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % bound;
    }
  }

 private:
  std::uint64_t state_;
};

}  // namespace dtlab::design::detail
