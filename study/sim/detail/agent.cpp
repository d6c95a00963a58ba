// TrialRun (agent.h): the simulated clock, frames, poses and input events of
// one trial. Mouse sensitivity is 0.005 radians per pixel (a common orbit and
// mouse-look default), so a drag of 45 degrees is 157 pixels of cursor motion.
#include "study/sim/detail/agent.h"

#include <cmath>

namespace dtlab::sim::detail {

namespace {
constexpr double kRadPerPixel = 0.005;
constexpr double kReferencePixels = 800.0 * 600.0;  // the article's screen (VII: 800 x 600 and up)
}  // namespace

TrialRun::TrialRun(const session::TrialSpec& s, const ModelParams& params, const Traits& tr, std::uint64_t seed,
                   render::Renderer& r, int w, int h)
    : spec(s), model(params), traits(tr), rng(seed), renderer(r), width(w), height(h), bounds(object_bounds(*s.scene)) {
  out.started_at = std::chrono::system_clock::now();
}

View TrialRun::look(const render::Camera& camera, float yaw, float pitch, std::span<const std::uint32_t> objects) {
  // An aid that follows the cursor is swept over the view (docs/sim.md, "Active aids"): a cursor
  // move and a fixation per spot, the frames of every spot recorded after its cursor event (replay
  // puts the aid where the cursor was), and each object seen as well as its best spot shows it.
  const bool mouse_turns_view = spec.scene->camera.mode == scene::CameraStart::Mode::walk;
  const std::vector<glm::vec2> spots = aid_spots(spec.frame, camera, mouse_turns_view, width, height);
  render::FrameSettings frame = spec.frame;
  View best;
  for (std::size_t k = 0; k < std::max<std::size_t>(1, spots.size()); ++k) {
    if (!spots.empty()) {
      if (k > 0) spend(scaled(model.aid_spot_s));
      frame.dt.searchlight_center = frame.lens.center = spots[k];
      out.events.push_back({t_, store::InputEvent::Kind::cursor, "", spots[k].x, spots[k].y});
    }
    auto looked = sim::look(renderer, camera, frame, width, height, objects, bounds);
    if (!looked) {
      if (!failure) failure = looked.error();
      t_ = std::max(t_, spec.time_limit_s);  // out of time: the agent stops looking
      View none;
      for (std::uint32_t o : objects) none.seen.push_back(Seen{o});
      return none;
    }
    View v = std::move(looked.value());
    for (double ms : v.frame_ms) {
      out.frame_ms.push_back(ms);
      out.poses.push_back(store::CameraPose{t_, camera.eye.x, camera.eye.y, camera.eye.z, yaw, pitch});
    }
    if (k == 0) {
      best = std::move(v);
      continue;
    }
    best.frame_ms.insert(best.frame_ms.end(), v.frame_ms.begin(), v.frame_ms.end());
    for (std::size_t i = 0; i < best.seen.size(); ++i) {
      best.seen[i].visible_px = std::max(best.seen[i].visible_px, v.seen[i].visible_px);
      best.seen[i].clear_px = std::max(best.seen[i].clear_px, v.seen[i].clear_px);
    }
  }
  ++trace.views;
  trace.aid_spots += static_cast<int>(spots.size());
  int visible = 0;
  for (const Seen& s : best.seen) visible += s.visible_px > 0;
  trace.visible.push_back(visible);
  return best;
}

double TrialRun::notice_probability(long visible_px) const {
  const double a = static_cast<double>(visible_px) * kReferencePixels / (static_cast<double>(width) * height);
  return traits.attention * (1.0 - std::exp(-a / model.notice_px));
}

void TrialRun::drag(double dyaw, double dpitch) {
  const double angle = std::hypot(dyaw, dpitch);
  const double d = scaled(model.drag_base_s + model.drag_s_per_rad * angle);
  const double cx = 0.5 * width, cy = 0.5 * height;
  const double dx = dyaw / kRadPerPixel, dy = -dpitch / kRadPerPixel;
  out.events.push_back({t_, store::InputEvent::Kind::button_down, "left", cx, cy});
  for (int k = 1; k <= 4; ++k)
    out.events.push_back({t_ + d * k / 5.0, store::InputEvent::Kind::cursor, "", cx + dx * k / 4.0, cy + dy * k / 4.0});
  out.events.push_back({t_ + d, store::InputEvent::Kind::button_up, "left", cx + dx, cy + dy});
  spend(d);
}

void TrialRun::turn(double dyaw) {
  const double d = scaled(model.turn_base_s + model.turn_s_per_rad * std::abs(dyaw));
  const double cx = 0.5 * width, cy = 0.5 * height;
  for (int k = 1; k <= 4; ++k)
    out.events.push_back({t_ + d * k / 4.0, store::InputEvent::Kind::cursor, "", cx - dyaw / kRadPerPixel * k / 4.0, cy});
  spend(d);
}

void TrialRun::walk(double distance) {
  if (distance <= 0) return;
  const double d = scaled(distance / model.walk_speed);
  out.events.push_back({t_, store::InputEvent::Kind::key_down, "Up", 0, 0});
  out.events.push_back({t_ + d, store::InputEvent::Kind::key_up, "Up", 0, 0});
  spend(d);
}

void TrialRun::finish(std::optional<store::Answer> answer, const std::string& text, double entry_s) {
  if (t_ >= spec.time_limit_s) {
    trace.timed_out = true;
    t_ = spec.time_limit_s;
  } else {
    spend(scaled(entry_s));
    if (t_ > spec.time_limit_s) t_ = spec.time_limit_s;
  }
  if (answer) out.events.push_back({t_, store::InputEvent::Kind::answer, text, 0, 0});
  out.answer = std::move(answer);
  out.completion_s = t_;
  out.ended_at = std::chrono::system_clock::now();
  trace.simulated_s = t_;
}

}  // namespace dtlab::sim::detail
