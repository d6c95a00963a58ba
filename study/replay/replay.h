// What a participant saw, again (`dtlab replay`): a recorded trial is looked
// up through the store's reader, its scene regenerated from the plan's seed
// under the protocol revision the session ran (the scene hash must equal the
// recorded one), and its recorded camera poses rendered with the trial's
// method into frames; the active searchlight follows the recorded cursor.
// WALKTHROUGH trials also get their walked path on the floor plan (path.h).
// Guarantees: frames come from the real renderer, nothing is re-implemented;
// the database is only read. Never: creates a GL context (the caller's must
// be current for render_frames).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"
#include "study/render/image.h"
#include "study/render/render.h"
#include "study/scene/scene.h"
#include "study/session/mapping.h"
#include "study/replay/path.h"
#include "study/store/read.h"

namespace dtlab::replay {

// One recorded trial with everything needed to show it again.
struct RecordedTrial {
  protocol::Protocol protocol;           // the revision the session ran under
  store::TrialRow row;                   // the result as recorded
  scene::Scene scene;                    // regenerated; scene.hash == row.scene_hash
  std::vector<store::CameraPose> poses;  // one per presented frame
  std::vector<store::InputEvent> events;
  std::optional<store::DisplayInfo> display;  // the display the session ran on, when recorded
};

// Reads trial `position` (1-based, as `dtlab plan` and the export) of `participant`. Errors:
// not_found (no such participant or recorded trial), conflict (the regenerated scene's hash
// differs from the recorded one: another build generates other scenes).
Result<RecordedTrial> load_trial(store::StudyReader& reader, const std::string& participant, int position);

// The walked paths of a participant's recorded `positions` as one SVG: a panel per WALKTHROUGH
// trial with recorded poses (each on its own building's plan; label "trial N, method"), three
// panels a row, under `title`; svg "" when none has poses. A trial whose scene this build
// generates differently (hash mismatch) is left out with the reason, not drawn on a wrong plan.
struct PathFigure {
  std::string svg;
  std::vector<std::string> left_out;  // "trial N: why"
};
Result<PathFigure> trials_path_svg(store::StudyReader& reader, const std::string& participant,
                                   const std::vector<int>& positions, const std::string& title);

// The camera of a recorded pose for a width x height view of the trial's scene.
render::Camera pose_camera(const scene::Scene& scene, const store::CameraPose& pose, int width, int height);

// Renders every `every`-th pose (the first and the last always) at width x height with the trial's
// method and settings, calling out(frame index 0-based, pose index, image) for each; a current
// GL 3.3 core context is needed.
Status render_frames(const RecordedTrial& trial, int width, int height, int every,
                     const std::function<Status(int frame, int pose, const render::Image&)>& out);

}  // namespace dtlab::replay
