// Loading and rendering a recorded trial (replay.h).
#include "study/replay/replay.h"

#include <algorithm>
#include <map>

#include "study/render/camera.h"

namespace dtlab::replay {

namespace {

Error no_trial(const store::StudyReader& reader, const std::string& participant, int position, std::size_t recorded) {
  return Error{reader.path(), 0, 0, "trial",
               "participant \"" + participant + "\" has no recorded trial " + std::to_string(position) + " (" +
                   std::to_string(recorded) + " recorded; trials are numbered from 1 as in dtlab plan)",
               ErrorKind::not_found};
}

// The protocol revision a recorded trial ran under.
Result<protocol::Protocol> trial_protocol(store::StudyReader& reader, const std::vector<store::Revision>& revisions,
                                          const store::TrialRow& row) {
  const auto rev = std::find_if(revisions.begin(), revisions.end(),
                                [&](const store::Revision& r) { return r.study_id == row.study_id; });
  if (rev == revisions.end())
    return Error{reader.path(), 0, 0, "studies", "the trial's protocol revision is missing", ErrorKind::internal};
  return protocol::load_protocol_text(rev->protocol_text, reader.path() + " (recorded protocol)");
}

// The trial's scene generated again; conflict when its hash is not the recorded one.
Result<scene::Scene> regenerate(const store::StudyReader& reader, const protocol::Protocol& p, const store::TrialRow& row) {
  auto setup = session::trial_setup(p, row.planned);
  if (!setup) return setup.error();
  auto sc = session::trial_scene(setup.value(), row.planned);
  if (!sc) return sc.error();
  if (sc->hash != row.scene_hash)
    return Error{reader.path(), 0, 0, "scene_hash",
                 "the regenerated scene of trial " + std::to_string(row.planned.position) + " has hash " +
                     sc->hash.substr(0, 12) + "..., the recorded one " + row.scene_hash.substr(0, 12) +
                     "...: this build generates other scenes than the one that ran the session",
                 ErrorKind::conflict};
  return sc;
}

}  // namespace

Result<RecordedTrial> load_trial(store::StudyReader& reader, const std::string& participant, int position) {
  auto rows = reader.trials(participant);
  if (!rows) return rows.error();
  const auto row = std::find_if(rows->begin(), rows->end(), [&](const store::TrialRow& r) { return r.planned.position == position; });
  if (row == rows->end()) return no_trial(reader, participant, position, rows->size());
  auto revisions = reader.revisions();
  if (!revisions) return revisions.error();
  auto p = trial_protocol(reader, *revisions, *row);
  if (!p) return p.error();
  RecordedTrial t;
  t.protocol = std::move(p.value());
  t.row = *row;
  auto sc = regenerate(reader, t.protocol, *row);
  if (!sc) return sc.error();
  t.scene = std::move(sc.value());
  auto poses = reader.poses(participant, position);
  if (!poses) return poses.error();
  t.poses = std::move(poses.value());
  auto events = reader.events(participant, position);
  if (!events) return events.error();
  t.events = std::move(events.value());
  auto sessions = reader.sessions();
  if (!sessions) return sessions.error();
  for (const auto& s : *sessions)
    if (s.participant == participant && !s.displays.empty()) t.display = s.displays.back().info;
  return t;
}

Result<PathFigure> trials_path_svg(store::StudyReader& reader, const std::string& participant,
                                   const std::vector<int>& positions, const std::string& title) {
  PathFigure figure;
  auto rows = reader.trials(participant);
  if (!rows) return rows.error();
  auto revisions = reader.revisions();
  if (!revisions) return revisions.error();
  std::map<std::int64_t, protocol::Protocol> protocols;  // by study_id: parsed once
  std::vector<PathPanel> panels;
  for (int position : positions) {
    const auto row = std::find_if(rows->begin(), rows->end(),
                                  [&](const store::TrialRow& r) { return r.planned.position == position; });
    if (row == rows->end()) return no_trial(reader, participant, position, rows->size());
    auto poses = reader.poses(participant, position);
    if (!poses && poses.error().kind != ErrorKind::not_found) return poses.error();
    if (!poses || poses->empty()) continue;
    auto known = protocols.find(row->study_id);
    if (known == protocols.end()) {
      auto p = trial_protocol(reader, *revisions, *row);
      if (!p) return p.error();
      known = protocols.emplace(row->study_id, std::move(p.value())).first;
    }
    auto sc = regenerate(reader, known->second, *row);
    if (!sc && sc.error().kind == ErrorKind::conflict) {
      figure.left_out.push_back("trial " + std::to_string(position) +
                                ": this build generates another scene than the one recorded (scene hash differs)");
      continue;
    }
    if (!sc) return sc.error();
    if (!sc->plan) continue;  // not a WALKTHROUGH trial: no floor plan to walk on
    const std::string label = "trial " + std::to_string(position) + ", " + row->planned.method;
    panels.push_back(path_panel(*sc->plan, sc->camera.position,
                                {walked_path(*sc, row->answer, std::move(poses.value()), label)}, 360));
  }
  if (!panels.empty()) figure.svg = panels_svg(panels, 3, title);
  return figure;
}

render::Camera pose_camera(const scene::Scene& scene, const store::CameraPose& pose, int width, int height) {
  const scene::CameraStart& c = scene.camera;
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(1, height));
  const auto yaw = static_cast<float>(pose.yaw), pitch = static_cast<float>(pose.pitch);
  if (c.mode == scene::CameraStart::Mode::walk)
    return render::walk_camera(glm::vec3(pose.x, pose.y, pose.z), yaw, pitch, c.fov_y, aspect, c.near_plane, c.far_plane);
  return render::orbit_camera(c.target, c.distance, yaw, pitch, c.fov_y, aspect, c.near_plane, c.far_plane);
}

Status render_frames(const RecordedTrial& trial, int width, int height, int every,
                     const std::function<Status(int frame, int pose, const render::Image&)>& out) {
  if (trial.poses.empty()) return {};
  auto setup = session::trial_setup(trial.protocol, trial.row.planned);
  if (!setup) return setup.error();
  auto frame = session::frame_settings(trial.protocol, *setup->rendering, width, height);
  if (!frame) return frame.error();
  auto renderer = render::Renderer::create(trial.scene);
  if (!renderer) return renderer.error();
  // The searchlight of the active mode (and an active lens) followed the cursor: the last cursor event before each frame,
  // scaled from the recorded display to this size.
  const double sx = trial.display ? static_cast<double>(width) / trial.display->width : 1.0;
  const double sy = trial.display ? static_cast<double>(height) / trial.display->height : 1.0;
  std::size_t next_event = 0;
  glm::vec2 cursor(width / 2.0f, height / 2.0f);
  const int n = static_cast<int>(trial.poses.size());
  int written = 0;
  for (int i = 0; i < n; ++i) {
    const store::CameraPose& pose = trial.poses[static_cast<std::size_t>(i)];
    while (next_event < trial.events.size() && trial.events[next_event].t_s <= pose.t_s) {
      const auto& e = trial.events[next_event++];
      if (e.kind == store::InputEvent::Kind::cursor) cursor = glm::vec2(e.x * sx, e.y * sy);
    }
    if (i % std::max(1, every) != 0 && i != n - 1) continue;
    render::FrameSettings s = frame.value();
    const glm::vec2 pointer =
        trial.scene.camera.mode == scene::CameraStart::Mode::walk ? glm::vec2(width / 2.0f, height / 2.0f) : cursor;
    technique::aim(s, pointer);
    if (auto drawn = (*renderer)->render_offscreen(pose_camera(trial.scene, pose, width, height), s, width, height); !drawn)
      return drawn.error();
    auto image = (*renderer)->read_color();
    if (!image) return image.error();
    if (Status st = out(written++, i, image.value()); !st) return st;
  }
  return {};
}

}  // namespace dtlab::replay
