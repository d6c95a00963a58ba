// Whether a protocol that loads can also run: every check the later stages
// make on a protocol's values (scene::validate for each task's scene,
// render::validate for each rendering at every viewport a session may use,
// the depth test's view and pairs for the first participants), plus bounds on
// the work of one frame, run before anything starts. `dtlab validate`,
// `dtlab simulate` and `dtlab demo` call it, so "valid" means "a session can
// run it". Guarantees: every diagnostic names the protocol file, the line and
// column of the key at fault and its field path; pure (no GL, no files, no
// database). Never: generates more scenes than the depth tests need.
#pragma once
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"
#include "study/session/session.h"

namespace dtlab::session {

// Viewport sides a session may use: `dtlab simulate` and `dtlab demo` take --width and --height
// in this range, and a participant window is kept within it.
inline constexpr int kMinViewportSide = 16;
inline constexpr int kMaxViewportSide = 4096;

// The viewports every rendering is checked at: the smallest and the largest a session may use
// (what depends on the viewport, the gradient in output pixels, grows with its area), the
// simulation default 160 x 120, and the window sizes 800 x 600 and 1920 x 1080.
std::vector<Viewport> checked_viewports();

// Depth tests are checked for the enrollment indexes 0 .. min(participants, this) - 1, at
// 160 x 120 (4:3) and 1920 x 1080 (16:9); the session prepares its own before its first trial.
inline constexpr int kDepthTestIndexesChecked = 8;

// The most targets one trial may have: every view the simulated participant looks at is
// rendered once per group of targets whose pixels it counts (study/sim/perception.h), so a
// trial's work grows with targets x objects; at 250 targets among 2000 objects a simulated
// trial takes some ten seconds on a software renderer (the reference has up to 50).
inline constexpr int kMaxTargets = 250;

// Work bounds for one frame of a method that runs passes per target (dt-seed): passes are
// targets x (gradient_width + 3), mask work is targets x (gradient_width + 2) x mask_resolution^2
// texels, with targets the most one trial of the task can have. The reference protocol needs
// 550 passes and 8.2e6 texels; at these bounds a simulated trial takes about half a minute on a
// software renderer (docs/protocol.md, "[rendering.<name>]").
inline constexpr long long kMaxPassesPerFrame = 2048;
inline constexpr long long kMaxMaskTexelsPerFrame = 1LL << 27;

// Every reason the protocol cannot run, as errors (file:line:column, field, message); empty if
// it can. `also` adds viewports to checked_viewports() (e.g. the one `dtlab simulate` will use).
// `p` must come from load_protocol.
std::vector<Diagnostic> validate_runnable(const protocol::Protocol& p, const std::vector<Viewport>& also = {});

// The most targets one trial of `task` can have (T1: target_ratio max x objects; T2: the lit
// cells of the largest letter; T3, T4: every placed object, all uncovered by transparency).
int max_targets(const protocol::Task& task);

}  // namespace dtlab::session
