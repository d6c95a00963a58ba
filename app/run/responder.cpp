// WindowResponder (responder.h): the screens around the trials -- the
// sequence's pages (consent, information, announcements, level instructions,
// breaks, practice feedback), instructions, training -- and the frame loop
// every screen shares.
// run_trial() is in trial.cpp, answer_questionnaire() in questionnaire.cpp.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/run/console.h"
#include "app/run/responder.h"
#include "app/run/screens.h"
#include "app/run/view.h"
#include "study/design/seeds.h"
#include "study/protocol/wording.h"
#include "study/render/gl_info.h"
#include "study/scene/generate.h"
#include "study/session/mapping.h"

namespace dtlab::run {

std::string default_instructions(const protocol::Protocol& p, protocol::TaskType type) {
  switch (type) {
    case protocol::TaskType::count_targets: return protocol::text(p, "instructions.count_targets");
    case protocol::TaskType::identify_letter: return protocol::text(p, "instructions.identify_letter");
    case protocol::TaskType::find_unique: return protocol::text(p, "instructions.find_unique");
    case protocol::TaskType::count_kind: return protocol::text(p, "instructions.count_kind");
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
}

void WindowResponder::on_trial_recorded(const session::TrialSpec&, const store::TrialRecord&) {
  console_->set_trial(nullptr);
}

Status WindowResponder::loop(const std::string& screen, const std::function<Status()>& draw3d,
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

Result<session::PageOutcome> WindowResponder::show_page(const session::PageSpec& page) {
  using Kind = session::PageSpec::Kind;
  session::PageOutcome out;
  out.shown_at = std::chrono::system_clock::now();
  const Clock::time_point start = Clock::now();
  const std::string go_on = protocol::text(protocol_, "button.continue");
  Status st = loop(page.screen, {}, [&] {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    Input& in = ui_.input();
    if (page.kind == Kind::pause && page.max_s > 0 && seconds >= page.max_s) {
      out.answer = "timed out";
      return true;
    }
    const bool may_go_on = page.kind != Kind::pause || page.skippable || seconds >= page.min_s;
    begin_panel("##page");
    ImGui::PushFont(ui_.heading_font());
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(page.title.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopFont();
    ImGui::Spacing();
    // A long text (consent) scrolls inside the panel; the buttons stay in view below it.
    const float text_h = std::min(ImGui::GetIO().DisplaySize.y * 0.6f,
                                  ImGui::CalcTextSize(page.text.c_str(), nullptr, false,
                                                      ImGui::GetContentRegionAvail().x).y + ui_.text_px());
    ImGui::BeginChild("##text", ImVec2(0, text_h));
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(page.text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndChild();
    if (page.kind == Kind::pause) {
      const double wait = page.min_s - seconds, left = page.max_s - seconds;
      std::string hint = may_go_on ? protocol::text(protocol_, "break.go_on")
                                   : protocol::text(protocol_, "break.wait",
                                                    {{"seconds", std::to_string(static_cast<int>(std::ceil(wait)))}});
      if (page.max_s > 0)
        hint += "\n" + protocol::text(protocol_, "break.ends_in",
                                      {{"seconds", std::to_string(static_cast<int>(std::ceil(left)))}});
      ImGui::TextDisabled("%s", hint.c_str());
    }
    ImGui::Spacing();
    const ImVec2 size(ui_.text_px() * 8, ui_.text_px() * 2);
    bool done = false;
    if (page.kind == Kind::consent) {
      const std::string agree = protocol::text(protocol_, "consent.agree");
      const std::string decline = protocol::text(protocol_, "consent.decline");
      const ImVec2 wide(std::max(size.x, ImGui::CalcTextSize(agree.c_str()).x + ui_.text_px() * 2), size.y);
      if (ui_.button(agree, wide)) out.answer = "agree";
      ImGui::SameLine();
      if (ui_.button(decline, ImVec2(std::max(size.x, ImGui::CalcTextSize(decline.c_str()).x + ui_.text_px() * 2),
                                     size.y)))
        out.answer = "decline";
      done = !out.answer.empty();
    } else {
      ImGui::BeginDisabled(!may_go_on);
      done = ui_.button(go_on, size) ||
             (may_go_on && (in.key_pressed(GLFW_KEY_SPACE) || in.key_pressed(GLFW_KEY_ENTER)));
      ImGui::EndDisabled();
      if (done) out.answer = "continue";
    }
    ImGui::End();
    return done;
  });
  if (!st) return st.error();
  out.ended_at = std::chrono::system_clock::now();
  return out;
}

Status WindowResponder::show_instructions(const session::TaskSetSpec& set) {
  const protocol::Task& task = *set.setup->task;
  const std::string text =
      (task.instructions.empty() ? default_instructions(protocol_, task.type) : task.instructions) +
      (set.time_limit_s > 0 ? "\n\n" + protocol::text(protocol_, "instructions.practise_first") : std::string());
  const std::string title = protocol::text(protocol_, set.resumed ? "instructions.welcome_back" : "instructions.next_task");
  const std::string go_on = protocol::text(protocol_, "button.continue");
  const auto shown_at = std::chrono::system_clock::now();
  Status st = loop("instructions " + set.task, {}, [&] {
    return message_panel(ui_, title, text, go_on) || ui_.input().key_pressed(GLFW_KEY_ENTER);
  });
  if (!st || !set.log_screen) return st;
  session::PageSpec page;
  page.protocol = &protocol_;
  page.screen = "instructions " + set.task;
  page.title = title;
  page.text = text;
  page.shown = set.task;
  return set.log_screen(page, session::PageOutcome{"continue", shown_at, std::chrono::system_clock::now()});
}

Status WindowResponder::show_training(const session::TaskSetSpec& set) {
  if (set.time_limit_s <= 0) return {};
  // A practice scene of the set's task and condition, never one of the recorded trials.
  const auto& tasks = set.setup->scenario->tasks;
  const protocol::Task* task = protocol::find_task(*set.setup->scenario, set.task);
  const auto task_index = task ? task - tasks.data() : 0;  // its place in the scenario: the training seed's domain
  const std::uint64_t seed =
      design::training_seed(protocol_.master_seed, static_cast<std::uint64_t>(set.enrollment_index),
                            static_cast<std::uint64_t>(set.block), static_cast<std::uint64_t>(task_index));
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
  Status st = loop("training " + set.task,
                   [&] { return (*view)->draw(ui_.width(), ui_.height(), glm::vec2(ui_.input().cursor())); },
                   [&] {
                     const double now = std::chrono::duration<double>(Clock::now() - start).count();
                     (*view)->steer(ui_.input(), now - last, !ImGui::GetIO().WantCaptureMouse);
                     last = now;
                     const double left = set.time_limit_s - now;
                     if (icon) find_this_panel(ui_, protocol_, *icon, sc->answer.target_kind);
                     char time[32];
                     std::snprintf(time, sizeof time, "%d:%02d", static_cast<int>(std::max(0.0, left)) / 60,
                                   static_cast<int>(std::max(0.0, left)) % 60);
                     const bool clicked = bottom_bar(ui_, protocol::text(protocol_, "training.bar", {{"time", time}}),
                                                     protocol::text(protocol_, "training.start"));
                     return left <= 0 || clicked || ui_.input().key_pressed(GLFW_KEY_ENTER) ||
                            ui_.input().key_pressed(GLFW_KEY_KP_ENTER) || console_->take_end_training();
                   });
  ui_.input().capture_cursor(false);
  return st;
}

Status WindowResponder::train(const session::TaskSetSpec& set) {
  if (Status st = show_instructions(set); !st) return st;
  const auto shown_at = std::chrono::system_clock::now();
  Status st = show_training(set);
  if (!st || !set.log_screen || set.time_limit_s <= 0) return st;
  session::PageSpec page;
  page.protocol = &protocol_;
  page.screen = "training " + set.task;
  page.shown = set.task;
  return set.log_screen(page, session::PageOutcome{"continue", shown_at, std::chrono::system_clock::now()});
}

}  // namespace dtlab::run
