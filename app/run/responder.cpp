// WindowResponder (responder.h): the screens around the trials -- break,
// instructions, training -- and the frame loop every screen shares.
// run_trial() is in trial.cpp, answer_questionnaire() in questionnaire.cpp.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

#include "app/run/console.h"
#include "app/run/responder.h"
#include "app/run/screens.h"
#include "app/run/view.h"
#include "study/design/seeds.h"
#include "study/render/gl_info.h"
#include "study/scene/generate.h"
#include "study/session/mapping.h"

namespace dtlab::run {

std::string default_instructions(protocol::TaskType type) {
  switch (type) {
    case protocol::TaskType::count_targets:
      return "Count all the RED objects in the scene. Drag with the left mouse button to turn the scene around "
             "its centre. When you know how many there are, press Enter and type the number.";
    case protocol::TaskType::identify_letter:
      return "The red CONES form one of the letters C, K, R, X or Y. Other red objects are not part of it. Drag with "
             "the left mouse button to turn the scene. When you know the letter, press Enter and choose it.";
    case protocol::TaskType::find_unique:
      return "Find the object shown in the upper left corner. Move with the arrow keys (Up, Down), turn with the "
             "mouse or Left/Right. When you have found it, press Enter and click where it is on the floor plan.";
    case protocol::TaskType::count_kind:
      return "Count the objects of the kind shown in the upper left corner, in the whole building. Move with the "
             "arrow keys (Up, Down), turn with the mouse or Left/Right. When you are done, press Enter and type the "
             "number.";
  }
  return "";
}

WindowResponder::WindowResponder(Ui& ui, store::Store& store, const protocol::Protocol& protocol,
                                 std::string participant, std::string experimenter)
    : ui_(ui), store_(store), protocol_(protocol), participant_(participant),
      console_(std::make_unique<Console>(ui, store, std::move(participant), std::move(experimenter))) {
  ui_.set_console([this] { console_->draw(); });
}

WindowResponder::~WindowResponder() { ui_.set_console({}); }

session::Viewport WindowResponder::viewport() const { return {ui_.width(), ui_.height()}; }

store::DisplayInfo WindowResponder::display() const {
  ui_.window().make_current();
  GLFWmonitor* m = glfwGetWindowMonitor(ui_.window().glfw());
  const char* name = m ? glfwGetMonitorName(m) : nullptr;
  return store::DisplayInfo{"window", ui_.width(), ui_.height(), ui_.refresh_hz(), render::current_gl_description(),
                            name ? name : ""};
}

bool WindowResponder::aborted() const { return console_->aborted(); }

void WindowResponder::on_session_start(const store::Session& session, const design::Plan& plan) {
  console_->set_session(session, static_cast<int>(plan.trials.size()));
  blocks_ = plan.trials.empty() ? 0 : plan.trials.back().block;
  last_block_ = 0;
  // A resumed session continues inside a block: no break before its first task set.
  for (const auto& t : plan.trials)
    if (t.position <= session.recorded) last_block_ = t.block;
}

void WindowResponder::on_trial_recorded(const session::TrialSpec&, const store::TrialRecord&) {
  console_->set_trial(nullptr);
}

Status WindowResponder::loop(const std::string& screen, const std::function<void()>& draw3d,
                             const std::function<bool()>& widgets) {
  console_->set_screen(screen);
  for (;;) {
    bool done = false;
    Status st = ui_.frame(screen, draw3d, [&] { done = widgets(); });
    if (!st) return st;
    if (console_->aborted())
      return Error{"", 0, 0, "session", "the experimenter aborted the session (it is abandoned)", ErrorKind::conflict};
    if (done) return {};
  }
}

Status WindowResponder::show_break(int finished_block) {
  const std::string text = "Block " + std::to_string(finished_block) + " of " + std::to_string(blocks_) +
                           " is done. Take a short break.\n\nPress Space or click Continue when you are ready.";
  return loop("break", {}, [&] {
    return message_panel(ui_, "Break", text, "Continue") || ui_.input().key_pressed(GLFW_KEY_SPACE);
  });
}

Status WindowResponder::show_instructions(const session::TaskSetSpec& set) {
  const protocol::Task& task = *set.setup->task;
  const std::string text = (task.instructions.empty() ? default_instructions(task.type) : task.instructions) +
                           "\n\nFirst you can practise freely in a scene like the ones to come.";
  const std::string title = set.resumed ? "Welcome back" : "Next task";
  return loop("instructions " + set.task, {}, [&] {
    return message_panel(ui_, title, text, "Continue") || ui_.input().key_pressed(GLFW_KEY_ENTER);
  });
}

Status WindowResponder::show_training(const session::TaskSetSpec& set) {
  if (set.time_limit_s <= 0) return {};
  // A practice scene of the set's task and condition, never one of the recorded trials:
  // seed = mix64(participant_seed(M, k), kTrainingDomain + 64 * block + task index).
  int task_index = 0;
  for (std::size_t i = 0; i < set.setup->scenario->tasks.size(); ++i)
    if (set.setup->scenario->tasks[i].id == set.task) task_index = static_cast<int>(i);
  const std::uint64_t seed = mix64(design::participant_seed(protocol_.master_seed, static_cast<std::uint64_t>(set.enrollment_index)),
                                   kTrainingDomain + 64ULL * static_cast<std::uint64_t>(set.block) +
                                       static_cast<std::uint64_t>(task_index));
  auto sc = scene::generate(set.setup->kind, set.setup->scene_task, seed, set.setup->params);
  if (!sc) return sc.error();
  auto frame = session::frame_settings(protocol_, *set.setup->rendering, ui_.width(), ui_.height());
  if (!frame) return frame.error();
  auto view = SceneView::create(sc.value(), frame.value());
  if (!view) return view.error();
  std::unique_ptr<Texture> icon;
  if (!sc->answer.target_kind.empty()) {
    auto t = icon_texture(sc->answer.target_kind, static_cast<int>(ui_.text_px() * 4));
    if (t) icon = std::move(t.value());
  }
  ui_.input().capture_cursor((*view)->walking());
  const Clock::time_point start = Clock::now();
  double last = 0;
  Status st = loop("training " + set.task, [&] { (*view)->draw(ui_.width(), ui_.height(), glm::vec2(ui_.input().cursor())); },
                   [&] {
                     const double now = std::chrono::duration<double>(Clock::now() - start).count();
                     (*view)->steer(ui_.input(), now - last, !ImGui::GetIO().WantCaptureMouse);
                     last = now;
                     const double left = set.time_limit_s - now;
                     if (icon) find_this_panel(ui_, *icon, sc->answer.target_kind);
                     char line[160];
                     std::snprintf(line, sizeof line, "Practice: explore freely (%d:%02d left). Press Enter to start.",
                                   static_cast<int>(std::max(0.0, left)) / 60, static_cast<int>(std::max(0.0, left)) % 60);
                     const bool clicked = bottom_bar(ui_, line, "Start the trials");
                     return left <= 0 || clicked || ui_.input().key_pressed(GLFW_KEY_ENTER) ||
                            ui_.input().key_pressed(GLFW_KEY_KP_ENTER) || console_->take_end_training();
                   });
  ui_.input().capture_cursor(false);
  return st;
}

Status WindowResponder::train(const session::TaskSetSpec& set) {
  if (last_block_ > 0 && set.block != last_block_)
    if (Status st = show_break(last_block_); !st) return st;
  last_block_ = set.block;
  if (Status st = show_instructions(set); !st) return st;
  return show_training(set);
}

}  // namespace dtlab::run
