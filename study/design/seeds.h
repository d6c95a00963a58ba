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
//   training_seed(M, k, b, t) = mix64(participant_seed(M, k), kTrainingDomain + 64 b + t)
//   depth_test_seed(M, k, i) = mix64(participant_seed(M, k), kDepthTestDomain + i)
//
// M = master_seed, k = 0-based enrollment index, p = 1-based trial position,
// which = 0 for the scheme of [order], 1 for its nested scheme, b the block and
// t the task's index in its scenario of a practice scene, i the 0-based
// position of a depth-test item in the questionnaire. Every domain is a power
// of two plus a word in ASCII (kOrderDomain 2^63 + "order", kDepthTestDomain
// 2^62 + "depth", kTrainingDomain 2^61 + "train"): values no enrollment index
// or trial position (an int) can take, so no two derivations coincide. One
// place for all of them: a new random stream takes a new domain here.
#pragma once
#include <cstdint>

#include "study/common/hash.h"

namespace dtlab::design {

inline constexpr std::uint64_t kOrderDomain = 0x8000000000000000ULL + 0x6f72646572ULL;      // 2^63 + "order"
inline constexpr std::uint64_t kDepthTestDomain = 0x4000000000000000ULL + 0x6465707468ULL;  // 2^62 + "depth"
inline constexpr std::uint64_t kTrainingDomain = 0x2000000000000000ULL + 0x747261696eULL;   // 2^61 + "train"

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

// Seed of the practice scene before block `block`'s task `task_index` (its index in the scenario).
constexpr std::uint64_t training_seed(std::uint64_t master, std::uint64_t index, std::uint64_t block,
                                      std::uint64_t task_index) {
  return mix64(participant_seed(master, index), kTrainingDomain + 64 * block + task_index);
}

// Seed of the depth-test item at 0-based `item_position` of the questionnaire.
constexpr std::uint64_t depth_test_seed(std::uint64_t master, std::uint64_t index, std::uint64_t item_position) {
  return mix64(participant_seed(master, index), kDepthTestDomain + item_position);
}

}  // namespace dtlab::design
