// Today's random streams, written down as literal numbers: the first outputs
// of every generator a recorded seed goes through (scene, design, session and
// simulated participants) and the draws its callers make from them (bounded
// integers, doubles, normals, a shuffle). A scene, a plan or a simulated
// answer reproduces from its stored seed only while these hold: a failure
// here means stored studies no longer reproduce. Never regenerate these
// numbers to make a change pass; the values were printed by the generators
// as they stood before they became one family (study/common/random.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "study/common/random.h"

namespace dtlab {
namespace {

using Scene = SceneRandom;
using Design = Random<SplitMix64>;

const std::vector<std::uint64_t> kBounds = {1, 2, 3, 6, 10, 1000, 1000003};

// The scene generators' xoshiro256** stream, seeded by (seed, stream).
TEST(RandomStreams, SceneRawOutputs) {
  Scene a(1, 0);
  for (std::uint64_t v : {0x6f0c221987108fb2ULL, 0x068a99bcd127fe03ULL, 0x35c925a786232a40ULL, 0x028a0078abb13302ULL})
    EXPECT_EQ(a.next(), v);
  Scene b(18446744073709551615ULL, 3);
  for (std::uint64_t v : {0xc2057f54f9c0a709ULL, 0x4764f4b4bedee482ULL, 0xc65bc56f8a00b391ULL, 0xf2bbfef169f17a09ULL})
    EXPECT_EQ(b.next(), v);
}

TEST(RandomStreams, SceneDraws) {
  Scene r(31, 1);
  const std::vector<std::uint64_t> below = {0, 1, 1, 4, 0, 992, 246408};
  for (std::size_t i = 0; i < kBounds.size(); ++i) EXPECT_EQ(r.below(kBounds[i]), below[i]) << "n = " << kBounds[i];
  // A bound above 2^63 rejects about half the raw values: the threshold's exact value shows.
  EXPECT_EQ(r.below((1ULL << 63) + 1), 1335963699746337971ULL);
  for (int v : {2, 3, -5, 4}) EXPECT_EQ(r.between(-5, 5), v);
  EXPECT_EQ(r.between(-2147483647 - 1, 2147483647), -247136855);
  for (double v : {0x1.829a598a16d2cp-3, 0x1.20bc11362c53p-2, 0x1.33fd953a5c951p-1}) EXPECT_EQ(r.uniform(), v);
  for (double v : {-0x1.641b4580025fap+0, 0x1.7211df3f3e67ep+0, -0x1.e91ffc3fd28dap-1}) EXPECT_EQ(r.uniform(-2.5, 7.0), v);
}

// The design stage's SplitMix64 (random orders). Seed 0's outputs are also
// Vigna's splitmix64.c reference values (tests/common/test_hash.cpp).
TEST(RandomStreams, DesignRawOutputsAndDraws) {
  Design a(0);
  for (std::uint64_t v : {0xe220a8397b1dcdafULL, 0x6e789e6aa1b965f4ULL, 0x06c45d188009454fULL, 0xf88bb8a8724c81ecULL})
    EXPECT_EQ(a.next(), v);
  Design r(42);
  const std::vector<std::uint64_t> below = {0, 1, 0, 0, 0, 62, 746268};
  for (std::size_t i = 0; i < kBounds.size(); ++i) EXPECT_EQ(r.below(kBounds[i]), below[i]) << "n = " << kBounds[i];
  EXPECT_EQ(r.below((1ULL << 63) + 1), 5545679290133000099ULL);
}

// The session's and the simulated participants' stream (questionnaire pair
// order, agents' traits and answers).
TEST(RandomStreams, SessionAndSimulationRawOutputs) {
  Stream a(0);
  for (std::uint64_t v : {0x5cc60547776902baULL, 0x2a4c004b6ae97d7fULL, 0xfccac7c96d3a1e78ULL, 0x93df7413971b78d9ULL})
    EXPECT_EQ(a.next(), v);
}

TEST(RandomStreams, SessionAndSimulationDraws) {
  Stream r(7);
  const std::vector<std::uint64_t> below = {0, 1, 0, 5, 2, 38, 611132};
  for (std::size_t i = 0; i < kBounds.size(); ++i) EXPECT_EQ(r.below(kBounds[i]), below[i]) << "n = " << kBounds[i];
  for (double v : {0x1.bd9cc1a8fda36p-1, 0x1.3150b158ba51cp-3, 0x1.bcb9d9b3da414p-1}) EXPECT_EQ(r.uniform(), v);
  for (double v : {0x1.6f0a4a2e24ca3p+1, -0x1.49a99950476f4p-1}) EXPECT_EQ(r.uniform(-1.0, 3.0), v);
  for (bool v : {false, false, false, false, true, false}) EXPECT_EQ(r.chance(0.3), v);
  // Box-Muller goes through libm's log and cos: pinned for this build's libm
  // (glibc), the promise the simulated participants make (study/common/stream.h).
  for (double v : {-0x1.381e86944637fp+0, 0x1.b22ebf8b2d5e5p+0, -0x1.205f01de310a2p-5}) EXPECT_EQ(r.normal(), v);
  EXPECT_EQ(r.normal(10.0, 2.0), 0x1.5e5b308ee773fp+3);
  // The session's shuffle (study/session/questionnaire.cpp): Fisher-Yates from the back.
  std::vector<int> v{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  r.shuffle(v);
  EXPECT_EQ(v, (std::vector<int>{8, 0, 9, 5, 3, 7, 4, 2, 6, 1}));
}

}  // namespace
}  // namespace dtlab
