// The layout of the frame-time audit (layout.h) from its FramesResult: the
// table per condition with its notes (the renderers named), what simulated
// frames are, and what the numbers say: no person's screen to check, no
// confound, or the warnings (repeated at the top by lay_out_overview).
// Computes nothing; every threshold it prints is in the result.
#include <cmath>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/layout.h"

namespace dtlab::report::detail {
namespace {

// The sentence that labels simulated frames with their size and renderer.
std::string simulated_text(const FramesResult& g) {
  std::string size_list;
  for (const auto& x : g.simulated_sizes) size_list += (size_list.empty() ? "" : ", ") + x;
  return "Simulated frames: the simulated participants' trials were rendered offscreen" +
         (size_list.empty() ? std::string() : " at " + size_list + " pixels") +
         (g.software_renderer ? ", by a software rasterizer on the CPU" : "") +
         ". Their frame rates measure this machine's rendering at that size, not what a participant's screen "
         "would show; they say nothing about fluency in a real session.";
}

// The per-condition table of the audit (without its notes).
Table frames_table(const FramesResult& fr) {
  Table t;
  t.id = "table-frames";
  t.caption = "Frame times per condition: median frame rate, late frames, the warm-up frame and the 95th percentile.";
  t.header = {"Condition", "Method", "Display", "Trials", "Frames", "Display Hz", "Median fps", "Late frames",
              "First frame (ms)", "p95 (ms)", "Slow trials"};
  t.text_columns = 3;
  for (const auto& c : fr.conditions)
    t.rows.push_back({c.condition, c.method, c.display.empty() ? kDash : c.display, integer(c.trials),
                      integer(c.frames),
                      c.trials_with_frames == 0 ? kDash   // no trial with frames: no rate
                                                : fixed(c.display_hz, 0) + (c.display_hz_known ? "" : " (assumed)"),
                      fixed(c.median_fps, 1) + (c.below_display ? " (below display)" : ""),
                      c.steady_frames > 0 ? integer(c.late_frames) + " (" + percent(c.late_share) + ")" : kDash,
                      fixed(c.median_first_ms, 1), fixed(c.median_p95_ms, 1),
                      c.p95_trials == 0 ? kDash : integer(c.slow_trials) + " (" + percent(c.slow_share) + ")"});
  return t;
}

// The table with its notes, then what the numbers say (simulated frames, no confound, or the warnings).
void frames_layout(Section& s, const FramesResult& fr) {
  const double threshold = fr.threshold_ms;
  const double min_fps = fr.min_fps;
  Table t = frames_table(fr);
  t.notes.push_back("Display: the kind and framebuffer size the session recorded (window: a participant's screen; "
                    "headless: offscreen, simulated). Median fps: 1000 / the median over trials of each trial's "
                    "median frame time after its first frame (its mean in databases written before frame timing "
                    "was split). Late frames: frames after the first that took more than 1.5 display intervals, "
                    "share of those frames. First frame: median over trials (warm-up, not in the other columns). "
                    "p95: median over trials of each trial's 95th-percentile frame time (all frames). Slow trials: "
                    "p95 above " + fixed(threshold, 1) + " ms (--frame-threshold-ms). Below display: on a display of "
                    "known rate, the median frame took more than " + fixed(100 * fr.below_tolerance, 0) +
                    "% longer than a refresh interval.");
  if (!fr.renderers.empty()) {
    std::string list;
    for (const auto& r : fr.renderers) list += (list.empty() ? "" : "; ") + ("`" + r + "`");
    t.notes.push_back("Renderer: " + list + ".");
  }
  s.add(std::move(t));
  if (fr.simulated_frames) s.text(simulated_text(fr));
  if (!fr.people)
    s.text("Every trial with frames was a simulated participant's: there is no participant's screen to check for a "
           "render-cost confound.");
  else if (fr.warnings.empty())
    s.text("Every condition rendered at a median of at least " + fixed(min_fps, 0) + " fps and the conditions' "
           "median frame rates are within " + fixed(100 * (fr.rate_spread - 1), 0) + "% of each other.");
  else
    s.add(Callout{"warning", "Render cost may confound completion time", fr.warnings});
}

}  // namespace

void lay_out_frames(Layout& out, const FramesResult& result) {
  const double threshold = result.threshold_ms;
  const double min_fps = result.min_fps;
  Section s{"frames", "Frame-time audit", 2, {}};
  s.text("Rendering speed per condition, from the frame times recorded with every trial. The median frame rate "
         "is over the trials' median frame time after their first frame; the first frame of a trial (scene upload "
         "and first present: warm-up) is reported apart. A frame is late when it took more than 1.5 display "
         "intervals, i.e. missed a refresh (" + fixed(result.assumed_hz, 0) + " Hz where the display's rate is unknown). A "
         "trial is slow when its 95th-percentile frame time exceeds " + fixed(threshold, 1) + " ms (" +
         fixed(min_fps, 0) + " fps). If conditions render at different speeds, completion time may measure "
         "render cost as well as the condition's effect on the participant.");
  if (result.trials_with_frames == 0)
    s.text("No trial in the database recorded frame times (frame_count = 0 everywhere): the trials were not "
           "rendered while they ran. The audit has nothing to check.");
  else
    frames_layout(s, result);
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail
