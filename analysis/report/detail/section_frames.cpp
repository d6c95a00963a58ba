// The frame-time audit: per condition, from the frame statistics the store
// keeps per trial (schema v3: the first frame apart, the median of frames
// 2..n, the frames later than 1.5 display intervals, the display's rate) and
// the display each session recorded (kind, framebuffer size, renderer): the
// median frame rate, the share of late frames, the warm-up frame, the p95
// and the trials whose p95 exceeded --frame-threshold-ms. It speaks up: a
// condition rendered below the threshold's rate (30 fps by default), or
// conditions whose median rates differ by more than 25%, give a warning (the
// top of the report repeats it), because render cost then may confound
// completion time. Computes the FramesResult only, with every threshold the
// layout prints (layout_frames.cpp); never claims fluency the numbers do not
// show.
#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// A condition is below the display's rate when its median steady frame takes more than this share
// of a refresh interval over it (vsync holds a fluid frame to the interval, give or take jitter).
constexpr double kBelowDisplayTolerance = 0.05;
// Two conditions' median frame rates "differ" when the faster is more than this much faster.
constexpr double kRateSpread = 1.25;
// The display rate late frames are counted against when the display's is unknown (store::frame_stats).
constexpr double kAssumedHz = 60;

// "headless 160 × 120" from a trial's display record; "" when none is recorded.
std::string display_text(const TrialRow& t) {
  if (t.display_kind.empty()) return "";
  return t.display_kind + (t.display_width > 0 ? " " + std::to_string(t.display_width) + " × " +
                                                     std::to_string(t.display_height)
                                               : std::string());
}

// True for a renderer string of a software rasterizer (Mesa's llvmpipe, softpipe, swrast).
bool software(const std::string& renderer) {
  for (const char* s : {"llvmpipe", "softpipe", "swrast", "Software"})
    if (renderer.find(s) != std::string::npos) return true;
  return false;
}

struct ConditionFrames {
  std::string name, method;
  long long trials = 0, frames = 0, slow = 0, late = 0, steady_frames = 0;
  std::vector<double> rate_ms;  // per trial: its steady median frame time (its mean in files before schema v3)
  std::vector<double> people_ms;  // the same, of people's trials only (simulated frames confound nothing)
  std::vector<double> first, p95, hz;
  std::set<std::string> displays;
  double fps() const { const double m = median(rate_ms); return m > 0 ? 1000 / m : NAN; }
  double people_fps() const { const double m = median(people_ms); return m > 0 ? 1000 / m : NAN; }
};

struct Gathered {
  std::vector<ConditionFrames> conds;            // one per protocol condition, in order
  std::set<std::string> renderers;               // every renderer string of the analysed trials
  std::set<std::string> simulated_sizes;         // "160 × 120": framebuffers of simulated participants' trials
  bool simulated_frames = false;                 // a simulated participant's trial has frames
};

// The frame statistics of the analysed trials, per condition.
Gathered gather(const Context& ctx, double threshold) {
  Gathered g;
  for (const auto& cond : ctx.design.protocol->conditions) {
    ConditionFrames c;
    c.name = cond.name;
    for (const auto& tr : ctx.data.trials) {
      if (!ctx.analysed(tr)) continue;
      bool same = true;
      for (size_t f = 0; f < tr.level_index.size(); ++f) same = same && tr.level_index[f] == cond.levels[f];
      if (!same) continue;
      ++c.trials;
      c.method = tr.planned.method;
      if (tr.frames.frames <= 0 || !tr.frames.mean_ms) continue;
      c.frames += tr.frames.frames;
      c.rate_ms.push_back(tr.frames.steady_median_ms.value_or(*tr.frames.mean_ms));
      if (tr.frames.first_ms) c.first.push_back(*tr.frames.first_ms);
      if (tr.frames.p95_ms) {
        c.p95.push_back(*tr.frames.p95_ms);
        c.slow += *tr.frames.p95_ms > threshold ? 1 : 0;
      }
      if (tr.frames.late) {
        c.late += *tr.frames.late;
        c.steady_frames += tr.frames.frames - 1;
      }
      c.hz.push_back(tr.frames.refresh_hz.value_or(kAssumedHz));
      if (!tr.display_kind.empty()) c.displays.insert(display_text(tr));
      if (!tr.renderer.empty()) g.renderers.insert(tr.renderer);
      if (std::find(ctx.simulated.begin(), ctx.simulated.end(), tr.participant) != ctx.simulated.end()) {
        g.simulated_frames = true;
        if (tr.display_width > 0)
          g.simulated_sizes.insert(std::to_string(tr.display_width) + " × " + std::to_string(tr.display_height));
      } else {
        c.people_ms.push_back(c.rate_ms.back());
      }
    }
    g.conds.push_back(std::move(c));
  }

  return g;
}

// One condition's row of the audit, from its frames gathered (`known_hz`: some trial recorded its display's rate).
FramesResult::Condition condition_row(const ConditionFrames& c, bool known_hz) {
  FramesResult::Condition r;
  r.condition = c.name;
  r.method = c.method;
  for (const auto& x : c.displays) r.display += (r.display.empty() ? "" : "; ") + x;
  r.trials = c.trials;
  r.trials_with_frames = static_cast<long long>(c.rate_ms.size());
  r.frames = c.frames;
  r.display_hz = median(c.hz);
  r.display_hz_known = known_hz;
  r.median_fps = c.fps();
  r.median_steady_ms = median(c.rate_ms);
  r.below_display = known_hz && r.median_steady_ms > (1 + kBelowDisplayTolerance) * 1000 / r.display_hz;
  r.late_frames = c.late;
  r.steady_frames = c.steady_frames;
  r.late_share = c.steady_frames > 0 ? static_cast<double>(c.late) / c.steady_frames : NAN;
  r.median_first_ms = median(c.first);
  r.median_p95_ms = median(c.p95);
  r.slow_trials = c.slow;
  r.p95_trials = static_cast<long long>(c.p95.size());
  r.slow_share = c.p95.empty() ? NAN : static_cast<double>(c.slow) / static_cast<double>(c.p95.size());
  return r;
}

// The audit per condition and the warnings its numbers give.
FramesResult frames_result(const Context& ctx, const Gathered& g, double threshold) {
  FramesResult out;
  out.threshold_ms = threshold;
  out.min_fps = 1000 / threshold;
  out.rate_spread = kRateSpread;
  out.below_tolerance = kBelowDisplayTolerance;
  out.assumed_hz = kAssumedHz;
  const bool known_hz = std::any_of(ctx.data.trials.begin(), ctx.data.trials.end(),
                                    [](const TrialRow& tr) { return tr.frames.refresh_hz.has_value(); });
  const ConditionFrames* fastest = nullptr;
  const ConditionFrames* slowest = nullptr;
  for (const auto& c : g.conds) {
    out.conditions.push_back(condition_row(c, known_hz));
    const FramesResult::Condition& r = out.conditions.back();
    out.trials_with_frames += r.trials_with_frames;
    if (r.below_display) out.below.push_back(c.name);
    // The confound warnings look at people's frames only: a simulated participant's offscreen frames
    // are no screen anyone watched (simulated_text says what they are).
    if (const double people = c.people_fps(); std::isfinite(people)) {
      if (people < out.min_fps)
        out.warnings.push_back(c.name + (c.method == c.name ? "" : " (" + c.method + ")") + " rendered at a median " +
                               fixed(people, 1) + " fps, below " + fixed(out.min_fps, 0) + " fps" +
                               (c.p95.empty() ? "" : "; " + percent(r.slow_share, 0) + " of its trials were slow") +
                               ".");
      if (!fastest || people > fastest->people_fps()) fastest = &c;
      if (!slowest || people < slowest->people_fps()) slowest = &c;
    }
  }
  if (fastest && slowest && fastest->people_fps() > kRateSpread * slowest->people_fps())
    out.warnings.push_back("Median frame rates differ by more than " + fixed(100 * (kRateSpread - 1), 0) +
                           "% between conditions: " + fastest->name + " " + fixed(fastest->people_fps(), 1) + " fps, " +
                           slowest->name + " " + fixed(slowest->people_fps(), 1) + " fps (" +
                           fixed(fastest->people_fps() / slowest->people_fps(), 1) + " times).");
  return out;
}

}  // namespace

FramesResult section_frames(Context& ctx) {
  const double threshold = ctx.options.frame_threshold_ms;
  const Gathered g = gather(ctx, threshold);
  FramesResult result = frames_result(ctx, g, threshold);
  result.renderers.assign(g.renderers.begin(), g.renderers.end());
  result.simulated_sizes.assign(g.simulated_sizes.begin(), g.simulated_sizes.end());
  result.simulated_frames = g.simulated_frames;
  result.software_renderer =
      std::any_of(g.renderers.begin(), g.renderers.end(), [](const std::string& r) { return software(r); });
  result.people =
      std::any_of(g.conds.begin(), g.conds.end(), [](const ConditionFrames& c) { return !c.people_ms.empty(); });
  for (const auto& w : result.warnings) result.tally.warnings.push_back("frame-time audit: " + w);
  return result;
}

}  // namespace dtlab::report::detail
