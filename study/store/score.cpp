// Score columns and frame-time statistics; see score.h for the definitions.
// The schema (detail/schema_tables.cpp) checks the same formulas as CHECK
// constraints, so a change here must change there too.
#include "study/store/score.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dtlab::store {

Scores score(const std::optional<Answer>& answer, const Answer& truth) {
  Scores s;
  if (!answer) return s;
  if (answer->index() != truth.index())
    throw std::invalid_argument("store::score: the answer's kind differs from the truth's kind");
  if (const auto* t = std::get_if<Count>(&truth)) {
    const std::int64_t a = std::get<Count>(*answer).n;
    s.signed_error = a - t->n;
    if (t->n != 0) s.rel_error = static_cast<double>(a > t->n ? a - t->n : t->n - a) / static_cast<double>(t->n);
  } else if (const auto* l = std::get_if<Letter>(&truth)) {
    s.correct = std::get<Letter>(*answer).letter == l->letter;
  } else {
    const auto& p = std::get<Position>(truth);
    const auto& a = std::get<Position>(*answer);
    s.distance = std::hypot(a.x - p.x, a.z - p.z);
  }
  return s;
}

FrameStats frame_stats(std::span<const double> frame_ms, std::optional<double> refresh_hz) {
  FrameStats st;
  st.frames = static_cast<std::int64_t>(frame_ms.size());
  if (refresh_hz && !(std::isfinite(*refresh_hz) && *refresh_hz > 0))
    throw std::invalid_argument("store::frame_stats: refresh_hz must be finite and > 0");
  st.refresh_hz = refresh_hz;
  if (frame_ms.empty()) return st;
  st.first_ms = frame_ms.front();
  if (frame_ms.size() >= 2) {
    std::vector<double> steady(frame_ms.begin() + 1, frame_ms.end());
    std::sort(steady.begin(), steady.end());
    const std::size_t m = steady.size();
    st.steady_median_ms = m % 2 ? steady[m / 2] : (steady[m / 2 - 1] + steady[m / 2]) / 2;
    const double late_ms = 1.5 * 1000.0 / refresh_hz.value_or(kAssumedRefreshHz);
    st.late = static_cast<std::int64_t>(std::count_if(steady.begin(), steady.end(), [&](double v) { return v > late_ms; }));
  }
  for (double v : frame_ms)
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument("store::frame_stats: frame times must be finite and >= 0");
  // Mean: Neumaier-compensated sum, then one correction pass, so constant
  // frame times give exactly that value (a plain sum of 3600 x 16.6 does not).
  double sum = 0, carry = 0;
  for (double v : frame_ms) {
    const double t = sum + v;
    carry += std::abs(sum) >= std::abs(v) ? (sum - t) + v : (v - t) + sum;
    sum = t;
  }
  const double n = static_cast<double>(frame_ms.size());
  double mean = (sum + carry) / n;
  double drift = 0;
  for (double v : frame_ms) drift += v - mean;
  mean += drift / n;
  st.mean_ms = mean;
  if (frame_ms.size() >= 2) {
    // Corrected two-pass variance (Chan, Golub & LeVeque 1983): stable for
    // large offsets, exactly 0 for constant data.
    double ss = 0, d_sum = 0;
    for (double v : frame_ms) {
      const double d = v - mean;
      ss += d * d;
      d_sum += d;
    }
    st.sd_ms = std::sqrt(std::max(0.0, (ss - d_sum * d_sum / n) / (n - 1)));
  }
  std::vector<double> sorted(frame_ms.begin(), frame_ms.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t rank = (95 * sorted.size() + 99) / 100;  // ceil(0.95 n) in exact integer arithmetic
  st.p95_ms = sorted[rank - 1];
  st.max_ms = sorted.back();
  return st;
}

}  // namespace dtlab::store
