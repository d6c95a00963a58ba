// What a frame reports to the renderer's callers, and the target it draws
// into: the public face of the frame graph (detail/frame_graph.h), which
// callers never see. Plain data, no GL.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace dtlab::render {

// A framebuffer the caller owns (a window's default framebuffer, an output FBO).
struct ImportedTarget {
  unsigned framebuffer = 0;
  int width = 0;
  int height = 0;
};

// One record per declared pass, in declaration order.
struct PassRecord {
  std::string name;
  bool culled = false;       // removed by compile(): nothing read its outputs
  bool conditional = false;  // ran under conditional rendering
  std::optional<bool> ran;   // executed (for conditional passes: the query said yes); nullopt: unknown yet
  double ms = 0.0;           // CPU time (all threads) of the pass when profiled (glFinish around it)
};

struct FrameReport {
  std::vector<PassRecord> passes;
  std::vector<std::string> gl_errors;  // "pass 'name': GL_INVALID_OPERATION", in order
  double frame_ms = 0.0;               // CPU wall time from graph build to glFinish (0 if not timed)
  std::vector<std::string> passes_run() const;  // names of passes that ran (unknown counts as ran)
};

}  // namespace dtlab::render
