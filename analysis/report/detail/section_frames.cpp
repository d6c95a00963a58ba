// The frame-time audit: per condition, from the frame statistics the store
// keeps per trial (mean, sd, p95, max frame time in ms), the median of the
// trials' mean and p95 frame times, the worst p95, and the share of trials
// whose p95 exceeded the threshold (default 33.3 ms = 30 frames per second);
// and, where the trials ran on a display of known refresh rate (schema v3,
// `dtlab run`), the median steady frame rate against that rate and the late
// frames, flagging a condition that fell below the display's rate.
// A reviewer reads from it whether rendering was fluid in every condition,
// i.e. whether slow frames could explain a difference in completion time.
#include <algorithm>
#include <cmath>

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

}  // namespace

void section_frames(Context& ctx) {
  const Design& d = ctx.design;
  const double threshold = ctx.options.frame_threshold_ms;
  Section s{"frames", "Frame-time audit", 2, {}};
  s.text("Rendering speed per condition, from the frame-time statistics recorded with every trial. A trial counts "
         "as slow when its 95th-percentile frame time exceeds " + fixed(threshold, 1) + " ms (" +
         fixed(1000 / threshold, 0) + " frames per second), i.e. when more than 5% of its frames were slower than "
         "that. Dynamic transparency costs rendering time by design (the article measured 2.1x to 3.6x the frame "
         "time); what matters for the comparison is that every condition stayed fluid.");
  Table t;
  t.id = "table-frames";
  t.caption = "Frame times per condition (ms): medians over trials of each trial's mean and 95th percentile.";
  t.header = {"Condition", "Method", "Trials", "Frames", "Median of mean", "≈ fps", "Median of p95", "Worst p95",
              "Slow trials", "Display Hz", "Steady fps", "Late frames"};
  nlohmann::json jf = nlohmann::json::array();
  std::string csv = csv_line({"condition", "method", "trials", "trials_with_frames", "frames", "median_mean_ms",
                              "median_p95_ms", "max_p95_ms", "max_frame_ms", "slow_trials", "slow_share",
                              "display_hz", "median_steady_ms", "steady_fps", "late_frames", "below_display"});
  long long with_frames = 0;
  std::vector<std::string> below;
  for (const auto& cond : d.protocol->conditions) {
    std::vector<double> means, p95s, steady, rates;
    long long trials = 0, frames = 0, slow = 0, late = 0;
    double worst = NAN, max_frame = NAN;
    std::string method;
    for (const auto& tr : ctx.data.trials) {
      if (!ctx.analysed(tr)) continue;
      bool same = true;
      for (size_t f = 0; f < tr.level_index.size(); ++f) same = same && tr.level_index[f] == cond.levels[f];
      if (!same) continue;
      ++trials;
      method = tr.method;
      if (tr.frame_count <= 0 || !tr.frame_mean) continue;
      frames += tr.frame_count;
      means.push_back(*tr.frame_mean);
      if (tr.frame_p95) {
        p95s.push_back(*tr.frame_p95);
        worst = std::isnan(worst) ? *tr.frame_p95 : std::max(worst, *tr.frame_p95);
        slow += *tr.frame_p95 > threshold ? 1 : 0;
      }
      if (tr.frame_max) max_frame = std::isnan(max_frame) ? *tr.frame_max : std::max(max_frame, *tr.frame_max);
      if (tr.refresh_hz) {  // a display of known rate: the steady frames against it
        rates.push_back(*tr.refresh_hz);
        if (tr.frame_median) steady.push_back(*tr.frame_median);
        late += tr.late_frames.value_or(0);
      }
    }
    with_frames += static_cast<long long>(means.size());
    const double mm = median(means), mp = median(p95s);
    const double share = p95s.empty() ? NAN : static_cast<double>(slow) / static_cast<double>(p95s.size());
    const double hz = median(rates), ms = median(steady);
    const bool is_below = hz > 0 && ms > 0 && ms > (1 + kBelowDisplayTolerance) * 1000 / hz;
    if (is_below) below.push_back(cond.name);
    const std::string steady_fps = ms > 0 ? fixed(1000 / ms, 0) + (is_below ? " (below)" : "") : kDash;
    t.rows.push_back({cond.name, method, std::to_string(trials), std::to_string(frames), fixed(mm, 1),
                      mm > 0 ? fixed(1000 / mm, 0) : kDash, fixed(mp, 1), fixed(worst, 1),
                      p95s.empty() ? kDash : std::to_string(slow) + " (" + percent(share) + ")",
                      hz > 0 ? fixed(hz, 0) : kDash, steady_fps, rates.empty() ? kDash : std::to_string(late)});
    jf.push_back({{"condition", cond.name}, {"method", method}, {"trials", trials},
                  {"trials_with_frames", means.size()}, {"frames", frames}, {"median_mean_ms", num(mm)},
                  {"median_p95_ms", num(mp)}, {"max_p95_ms", num(worst)}, {"max_frame_ms", num(max_frame)},
                  {"slow_trials", slow}, {"slow_share", num(share)}, {"display_hz", num(hz)},
                  {"median_steady_ms", num(ms)}, {"late_frames", rates.empty() ? nlohmann::json() : nlohmann::json(late)},
                  {"below_display", is_below}});
    csv += csv_line({cond.name, method, std::to_string(trials), std::to_string(means.size()), std::to_string(frames),
                     csv_number(mm), csv_number(mp), csv_number(worst), csv_number(max_frame), std::to_string(slow),
                     csv_number(share), csv_number(hz), csv_number(ms), csv_number(ms > 0 ? 1000 / ms : NAN),
                     rates.empty() ? "NA" : std::to_string(late), is_below ? "TRUE" : "FALSE"});
  }
  if (with_frames == 0) {
    s.text("No trial in the database recorded frame times (frame_count = 0 everywhere): the trials were not "
           "rendered while they ran, as with simulated participants that answer without a display. The audit has "
           "nothing to check.");
  } else {
    t.notes.push_back("Frames: frames rendered in the condition's trials. ≈ fps = 1000 / median of the trials' mean "
                      "frame time. Slow trials: p95 frame time above " + fixed(threshold, 1) +
                      " ms, share of the trials with frame statistics. Display Hz, steady fps, late frames: only "
                      "trials shown on a display of known refresh rate (dtlab run); steady fps = 1000 / median of "
                      "the trials' median frame time after the first frame; late frames: steady frames that took "
                      "more than 1.5 refresh intervals. A condition is \"below\" when its steady frame time "
                      "exceeds the refresh interval by more than " + fixed(100 * kBelowDisplayTolerance, 0) + "%.");
    s.add(t);
    if (!below.empty()) {
      std::string names;
      for (const auto& n : below) names += (names.empty() ? "" : ", ") + n;
      s.text("Warning: rendering fell below the display's refresh rate in " + names +
             ". Completion times in these conditions may include waiting for frames; compare them with care.");
    }
  }
  ctx.json["frames"] = {{"threshold_ms", threshold},
                        {"trials_with_frames", with_frames},
                        {"below_display", below},
                        {"conditions", jf}};
  ctx.csv["frames.csv"] = csv;
  ctx.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail
