// Hashes must be identical on every machine: checked against published vectors.
#include <gtest/gtest.h>

#include "study/common/hash.h"

namespace {

// FIPS 180-2 appendix B.1 and the empty-string vector.
TEST(Sha256, MatchesFipsVectors) {
  EXPECT_EQ(dtlab::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(dtlab::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

// SplitMix64 reference outputs for seed 0 (Vigna's splitmix64.c: the first
// three outputs of the generator whose state starts at 0).
TEST(Mix64, MatchesSplitMix64Reference) {
  EXPECT_EQ(dtlab::mix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(dtlab::mix64(0x9e3779b97f4a7c15ULL), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(dtlab::mix64(2 * 0x9e3779b97f4a7c15ULL), 0x06c45d188009454fULL);
}

TEST(Mix64, CombiningIsOrderSensitive) {
  EXPECT_NE(dtlab::mix64(dtlab::mix64(1, 2), 3), dtlab::mix64(dtlab::mix64(1, 3), 2));
}

}  // namespace
