// Hashes that must give the same answer on every machine: SHA-256 (OpenSSL)
// for content identity of protocols and scenes, and SplitMix64 mixing for
// deriving seeds. Pure functions, no global state; never use std::hash here
// (it differs between standard libraries).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace dtlab {

std::string sha256_hex(std::string_view bytes);  // lowercase hex, 64 chars

// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijection on 64-bit
// integers with full avalanche. Used to derive seeds from tuples.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Combines a running seed with one more value: mix64(seed ^ mix64(value)).
constexpr std::uint64_t mix64(std::uint64_t seed, std::uint64_t value) {
  return mix64(seed ^ mix64(value));
}

}  // namespace dtlab
