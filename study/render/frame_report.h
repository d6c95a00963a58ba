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

// Scene-mesh draw calls and the triangles they submitted.
struct DrawCounts {
  long draws = 0;
  long triangles = 0;
};

// One record per declared pass, in declaration order.
struct PassRecord {
  std::string name;
  bool culled = false;       // removed by compile(): nothing read its outputs
  bool conditional = false;  // ran under conditional rendering
  std::optional<bool> ran;   // executed (for conditional passes: the query said yes); nullopt: unknown yet
  double ms = 0.0;           // CPU time (all threads) of the pass when profiled (glFinish around it)
  long draws = 0;            // when profiled: scene-mesh draw calls the pass issued (screen quads not counted)
  long triangles = 0;        // when profiled: triangles those draws submitted (conditional ones too)
};

// Occlusion culling's work in one frame (FrameSettings::occlusion_culling; docs/render.md).
struct CullingReport {
  bool ran = false;                    // on, and the scene has a floor plan (WALKTHROUGH)
  int occluders = 0;                   // drawn into the occluder depth (the nearest grid point's, in view)
  int objects_in_view = 0, objects_culled = 0;      // in the view frustum; of those, hidden by occluders
  long triangles_in_view = 0, triangles_culled = 0;
  int nodes_tested = 0, nodes_culled = 0;           // hierarchy nodes
  double ms = 0.0;             // CPU wall time of the test: occluder render, reduction, readback, maps, tree
  double readback_ms = 0.0;    // of which reading the small map back (waits for the occluder render)
  double preprocess_ms = 0.0;  // the occluder database, on the frame that built it (once per Renderer)
};

struct FrameReport {
  std::vector<PassRecord> passes;
  CullingReport culling;
  std::vector<std::string> gl_errors;  // "pass 'name': GL_INVALID_OPERATION", in order
  double frame_ms = 0.0;               // CPU wall time from graph build to glFinish (0 if not timed)
  std::vector<std::string> passes_run() const;  // names of passes that ran (unknown counts as ran)
};

}  // namespace dtlab::render
