// Score columns and frame statistics (store/score.h) on hand-computed cases,
// including the undefined relative error of a zero true count, missing
// answers, and frame times at a large offset (two-pass variance).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "study/store/score.h"

namespace dtlab::store {
namespace {

struct CountCase {
  std::int64_t answer, truth;
  std::optional<double> rel;
  std::int64_t signed_error;
};

TEST(Score, CountsGiveRelativeAndSignedError) {
  const CountCase cases[] = {
      {20, 20, 0.0, 0},        // exact
      {18, 20, 0.1, -2},       // under-counted: |18-20|/20
      {25, 20, 0.25, 5},       // over-counted
      {0, 7, 1.0, -7},         // answered zero
      {3, 0, std::nullopt, 3}, // truth 0: relative error undefined (NA), signed error defined
  };
  for (const auto& c : cases) {
    const Scores s = score(Answer{Count{c.answer}}, Answer{Count{c.truth}});
    ASSERT_EQ(s.signed_error, c.signed_error) << c.answer << " vs " << c.truth;
    ASSERT_EQ(s.rel_error.has_value(), c.rel.has_value());
    if (c.rel) {
      EXPECT_DOUBLE_EQ(*s.rel_error, *c.rel);
    }
    EXPECT_FALSE(s.correct.has_value());
    EXPECT_FALSE(s.distance.has_value());
  }
}

TEST(Score, LettersAreExactMatches) {
  EXPECT_EQ(score(Answer{Letter{"K"}}, Answer{Letter{"K"}}).correct, true);
  EXPECT_EQ(score(Answer{Letter{"X"}}, Answer{Letter{"K"}}).correct, false);
  EXPECT_EQ(score(Answer{Letter{"k"}}, Answer{Letter{"K"}}).correct, false);  // case-sensitive, documented
}

TEST(Score, PositionsGiveEuclideanDistanceInXZ) {
  EXPECT_DOUBLE_EQ(*score(Answer{Position{3, 4}}, Answer{Position{0, 0}}).distance, 5.0);
  // Large offsets: hypot does not lose the small difference.
  EXPECT_DOUBLE_EQ(*score(Answer{Position{1e8 + 3, -1e8}}, Answer{Position{1e8, -1e8 + 4}}).distance, 5.0);
}

TEST(Score, MissingAnswerGivesNoScores) {
  const Scores s = score(std::nullopt, Answer{Count{10}});
  EXPECT_FALSE(s.rel_error || s.signed_error || s.correct || s.distance);
}

TEST(Score, KindMismatchIsAPreconditionViolation) {
  EXPECT_THROW(score(Answer{Letter{"K"}}, Answer{Count{3}}), std::invalid_argument);
}

TEST(FrameStats, MeanSdNearestRankP95Max) {
  // 1..20 ms: mean 10.5, sample sd sqrt(35) (= sqrt(n(n+1)/12) for 1..n), p95 = sorted[ceil(19) - 1] = 19.
  std::vector<double> ms;
  for (int i = 20; i >= 1; --i) ms.push_back(i);
  const FrameStats s = frame_stats(ms);
  EXPECT_EQ(s.frames, 20);
  EXPECT_DOUBLE_EQ(*s.mean_ms, 10.5);
  EXPECT_DOUBLE_EQ(*s.sd_ms, std::sqrt(35.0));
  EXPECT_DOUBLE_EQ(*s.p95_ms, 19.0);
  EXPECT_DOUBLE_EQ(*s.max_ms, 20.0);
}

TEST(FrameStats, EdgeCases) {
  const FrameStats none = frame_stats({});
  EXPECT_EQ(none.frames, 0);
  EXPECT_FALSE(none.mean_ms || none.sd_ms || none.p95_ms || none.max_ms);
  const std::vector<double> one{7.0};
  const FrameStats single = frame_stats(one);
  EXPECT_EQ(*single.mean_ms, 7.0);
  EXPECT_FALSE(single.sd_ms.has_value());  // n - 1 = 0
  EXPECT_EQ(*single.p95_ms, 7.0);
  // Large offset, tiny spread: the two-pass sd is exact here (1e9 + {0,1,2}: sd 1).
  const std::vector<double> off{1e9, 1e9 + 1, 1e9 + 2};
  EXPECT_DOUBLE_EQ(*frame_stats(off).sd_ms, 1.0);
  // Zero variance: 3600 frames of 16.6 ms give mean 16.6 and sd 0 exactly
  // (regression: a plain sum gave mean 16.599999999999014 and sd 9.9e-13).
  const std::vector<double> flat(3600, 16.6);
  const FrameStats f = frame_stats(flat);
  EXPECT_EQ(*f.mean_ms, 16.6);
  EXPECT_EQ(*f.sd_ms, 0.0);
  EXPECT_EQ(*f.p95_ms, 16.6);
  const std::vector<double> bad{1.0, std::nan("")};
  EXPECT_THROW(frame_stats(bad), std::invalid_argument);
}

// Schema v3: the first frame (warm-up) apart; the median of the steady frames; late frames are
// steady frames slower than 1.5 display intervals (60 Hz when the display's rate is unknown).
TEST(FrameStats, WarmUpAndLateFramesApart) {
  // 500 (warm-up), then 16, 17, 25, 26, 40 ms. At 60 Hz late means > 25 ms: 26 and 40 -> 2.
  const std::vector<double> ms{500, 16, 17, 25, 26, 40};
  const FrameStats s = frame_stats(ms);
  EXPECT_EQ(*s.first_ms, 500.0);
  EXPECT_EQ(*s.steady_median_ms, 25.0);  // 16 17 25 26 40 -> 25
  EXPECT_EQ(*s.late, 2);
  EXPECT_FALSE(s.refresh_hz.has_value());
  // At 144 Hz late means > 10.4166... ms: every steady frame (5).
  const FrameStats fast = frame_stats(ms, 144.0);
  EXPECT_EQ(*fast.late, 5);
  EXPECT_EQ(*fast.refresh_hz, 144.0);
  // At 30 Hz late means > 50 ms: none; the warm-up frame never counts.
  EXPECT_EQ(*frame_stats(ms, 30.0).late, 0);
  // Even count: the mean of the middle two (16 17 | 25 26 -> 21).
  const std::vector<double> even{9, 16, 17, 25, 26};
  EXPECT_EQ(*frame_stats(even).steady_median_ms, 21.0);
  const std::vector<double> one{7.0};
  const FrameStats single = frame_stats(one);
  EXPECT_EQ(*single.first_ms, 7.0);
  EXPECT_FALSE(single.steady_median_ms || single.late);
  EXPECT_THROW(frame_stats(ms, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace dtlab::store
