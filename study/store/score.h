// Answers and their scores: the one place where a trial's score columns are
// computed from (answer, truth). Pure functions of their arguments; the store
// writes these values and its CHECK constraints reject any row whose scores
// disagree with its answer and truth, so a score is never computed twice in
// two different ways. Never depends on scene or session types.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>

namespace dtlab::store {

struct Count { std::int64_t n = 0; };        // T1, T4: a number of objects
struct Letter { std::string letter; };       // T2: one letter, e.g. "K"
struct Position { double x = 0, z = 0; };    // T3: a floor position in world units (x, z)

// What a participant answered, or the answer key. The alternative decides
// the score: counts get errors, letters correctness, positions a distance.
using Answer = std::variant<Count, Letter, Position>;

// The score columns of one trial. Missing-data policy: every member is
// nullopt when the participant gave no answer, and for members that do not
// apply to the answer's kind.
struct Scores {
  std::optional<double> rel_error;           // count: |answer - truth| / truth; nullopt if truth == 0 (undefined)
  std::optional<std::int64_t> signed_error;  // count: answer - truth (positive = over-counted)
  std::optional<bool> correct;               // letter: answer == truth (exact, case-sensitive)
  std::optional<double> distance;            // position: Euclidean distance in (x, z), world units
};

// Scores of `answer` against `truth` (STUDY.md, "Measures"). Precondition:
// a present answer has the same alternative as truth (else invalid_argument).
Scores score(const std::optional<Answer>& answer, const Answer& truth);

// Per-trial frame-time statistics from per-frame times in milliseconds (the first frame's time
// includes the trial's warm-up: scene upload, shader compile, first present).
struct FrameStats {
  std::int64_t frames = 0;               // number of frames rendered
  std::optional<double> mean_ms;         // compensated mean; nullopt when frames == 0
  std::optional<double> sd_ms;           // sample sd (n - 1, corrected two-pass); nullopt when frames < 2
  std::optional<double> p95_ms;          // 95th percentile, nearest rank: sorted[ceil(0.95 n) - 1]
  std::optional<double> max_ms;
  // Apart from the warm-up (schema v3):
  std::optional<double> first_ms;        // the first frame; nullopt when frames == 0
  std::optional<double> steady_median_ms;  // median of frames 2..n (mean of the middle two); nullopt when frames < 2
  std::optional<std::int64_t> late;      // frames 2..n slower than 1.5 display intervals; nullopt when frames < 2
  std::optional<double> refresh_hz;      // the display's refresh rate the late count used; nullopt: unknown (60 Hz used)
};

inline constexpr double kAssumedRefreshHz = 60.0;  // for late frames when the display's rate is unknown

// Summarises frame times (each finite, >= 0; else invalid_argument). `refresh_hz`: the display's
// refresh rate (> 0), nullopt when unknown (headless, simulated): late frames then count against 60 Hz.
FrameStats frame_stats(std::span<const double> frame_ms, std::optional<double> refresh_hz = std::nullopt);

}  // namespace dtlab::store
