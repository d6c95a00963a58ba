// The documented seed derivations of a study (also in docs/protocol.md).
// Guarantee: a trial's seed depends only on (master seed, enrollment index,
// trial position), so a plan is identical on every machine and never depends
// on what ran before, on the order row or on the conditions. Built only from
// dtlab::mix64 (study/common/hash.h): SplitMix64's finaliser, and
// mix64(s, v) = mix64(s ^ mix64(v)). All arithmetic is modulo 2^64.
//
//   participant_seed(M, k)   = mix64(mix64(M), k)
//   trial_seed(M, k, p)      = mix64(participant_seed(M, k), p)
//   order_seed(M, which)     = mix64(mix64(mix64(M), kOrderDomain), which)
//
// M = master_seed, k = 0-based enrollment index, p = 1-based trial position,
// which = 0 for the scheme of [order], 1 for its nested scheme. kOrderDomain is
// 2^63 + 0x6f72646572 ("order"), a value no enrollment index (int) can take,
// so order seeds never coincide with participant seeds.
#pragma once
#include <cstdint>

#include "study/common/hash.h"

namespace dtlab::design {

inline constexpr std::uint64_t kOrderDomain = 0x8000000000000000ULL + 0x6f72646572ULL;

// Seed of everything random about participant k (k >= 0).
constexpr std::uint64_t participant_seed(std::uint64_t master, std::uint64_t index) {
  return mix64(mix64(master), index);
}

// Seed of the trial at 1-based `position` of participant k's plan.
constexpr std::uint64_t trial_seed(std::uint64_t master, std::uint64_t index, std::uint64_t position) {
  return mix64(participant_seed(master, index), position);
}

// Seed of the random orders of a `scheme = "random"` ordering (which: 0 outer, 1 nested).
constexpr std::uint64_t order_seed(std::uint64_t master, std::uint64_t which) {
  return mix64(mix64(mix64(master), kOrderDomain), which);
}

}  // namespace dtlab::design
