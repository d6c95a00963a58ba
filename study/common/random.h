// The tree's one family of random generators: two engines and one set of draws.
// SplitMix64 (Steele, Lea & Flood 2014) for short streams, xoshiro256**
// (Blackman & Vigna 2018) for the scene generators' long ones; Random<Engine>
// makes every draw a caller needs (unbiased bounded integers, doubles, normals,
// shuffles) the same way for both. Seeds are derived with dtlab::mix64
// (hash.h); which seed goes where is study/design/seeds.h.
// Guarantees: the same seed gives the same values on every machine and compiler
// (integers and uniform doubles use only integer arithmetic and IEEE-754 basic
// operations; normal() also goes through libm's log and cos, so it is the same on
// every run of one build). The streams are those the scenes, plans, sessions
// and simulated participants recorded before this header existed
// (tests/common/test_random_streams.cpp pins them). Never: a global RNG,
// std::random_device, std::rand or std::*_distribution (their streams differ
// between standard libraries); no other file defines a generator.
#pragma once
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "study/common/hash.h"

namespace dtlab {

inline constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;  // SplitMix64's increment

// SplitMix64: output mix64(state), then state += golden gamma (splitmix64.c).
class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t state) : state_(state) {}
  constexpr std::uint64_t next() {  // the next 64 random bits
    const std::uint64_t r = mix64(state_);
    state_ += kGoldenGamma;
    return r;
  }

 private:
  std::uint64_t state_;
};

// xoshiro256** 1.0 (xoshiro256starstar.c).
class Xoshiro256StarStar {
 public:
  // The four state words as given (not all zero): the reference implementation's seeding.
  explicit constexpr Xoshiro256StarStar(const std::array<std::uint64_t, 4>& s) : s_(s) {}
  // Stream `stream` of `seed`: word i = mix64(mix64(seed, stream) + i * golden gamma), i = 0..3
  // (mix64 is a bijection, so at most one word is zero).
  constexpr Xoshiro256StarStar(std::uint64_t seed, std::uint64_t stream) : s_{} {
    const std::uint64_t base = mix64(seed, stream);
    for (std::size_t i = 0; i < 4; ++i) s_[i] = mix64(base + i * kGoldenGamma);
  }
  constexpr std::uint64_t next() {  // the next 64 random bits
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

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_;
};

// The draws, over either engine. Never draw twice in one expression
// (f(rng.uniform(), rng.uniform())): argument order differs between compilers.
template <class Engine>
class Random {
 public:
  template <class... Args>
    requires std::constructible_from<Engine, Args...>
  explicit constexpr Random(Args... engine_args) : engine_(engine_args...) {}  // the engine's constructor

  constexpr std::uint64_t next() { return engine_.next(); }  // the engine's next 64 bits

  // Uniform integer in [0, n), n >= 1: r % n over the raw values r >= 2^64 mod n (the rest
  // are drawn again), so every result is equally likely; a bound below 2^32 redraws with
  // probability under 2^-32, so the values equal the plain r % n nearly always.
  constexpr std::uint64_t below(std::uint64_t n) {
    if (n == 0) throw std::invalid_argument("Random::below: the bound must be at least 1");
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }

  // Uniform integer in [lo, hi], lo <= hi.
  constexpr int between(int lo, int hi) {
    if (lo > hi) throw std::invalid_argument("Random::between: lo must not exceed hi");
    return lo + static_cast<int>(below(static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo) + 1));
  }

  // Uniform double in [0, 1): the top 53 bits times 2^-53 (exact).
  constexpr double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  constexpr double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }  // in [lo, hi)
  constexpr bool chance(double p) { return uniform() < p; }                              // true with probability p

  // Standard normal by Box-Muller, one value per call (two uniforms, the first as 1 - u in (0, 1]).
  double normal() {
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  double normal(double mean, double sd) { return mean + sd * normal(); }  // N(mean, sd^2)

  // Fisher-Yates from the back: for i = size down to 2, swap v[i-1] with v[below(i)].
  template <class T>
  constexpr void shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(i)]);
  }

 private:
  Engine engine_;
};

// The scene generators' stream: xoshiro256** from (trial seed, stream number).
using SceneRandom = Random<Xoshiro256StarStar>;

// The session's, the simulated participants' and their questionnaires' stream:
// SplitMix64 started at seed x golden gamma + 0x632be59bd9b4e019 (output k is
// mix64((seed + k) x gamma + 0x632be59bd9b4e019), as recorded studies drew it).
class Stream : public Random<SplitMix64> {
 public:
  explicit constexpr Stream(std::uint64_t seed) : Random<SplitMix64>(seed * kGoldenGamma + 0x632be59bd9b4e019ULL) {}
};

}  // namespace dtlab
