// WindowResponder::run_trial (responder.h): the trial view and its answer
// input. The clock starts at the first frame actually presented (after its
// buffer swap) and stops when the answer is submitted; time paused from the
// console is subtracted. Every presented frame of the scene adds a frame
// time (swap to swap; the first one runs from the screen's start, the
// warm-up) and a camera pose; input is logged from the first present on.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <charconv>
#include <cstring>

#include "app/run/console.h"
#include "app/run/responder.h"
#include "app/run/screens.h"
#include "app/run/view.h"
#include "study/protocol/wording.h"
#include "study/scene/models.h"

namespace dtlab::run {

namespace {

enum class AnswerKind { count, letter, position };

AnswerKind kind_of(scene::Task t) {
  switch (t) {
    case scene::Task::T2: return AnswerKind::letter;
    case scene::Task::T3: return AnswerKind::position;
    default: return AnswerKind::count;
  }
}

// The answer screen's question, naming what was to be counted or found.
std::string question(const protocol::Protocol& p, const scene::Answer& a) {
  const std::string kind = a.target_kind.empty() ? "" : kind_name(p, a.target_kind);
  switch (a.task) {
    case scene::Task::T1: return protocol::text(p, "answer.count");
    case scene::Task::T2: return protocol::text(p, "answer.letter");
    case scene::Task::T3: return protocol::text(p, "answer.position", {{"kind", kind}});
    case scene::Task::T4: return protocol::text(p, "answer.kind_count", {{"kind", kind}});
  }
  return "";
}

// The answer widgets; sets `answer` (and a log text) when the participant submits.
struct AnswerInput {
  AnswerKind kind = AnswerKind::count;
  std::vector<std::string> letters;
  char number[16] = {};
  bool focus = true;
  std::string problem;
  std::optional<glm::vec2> mark;

  // True when submitted.
  bool draw(Ui& ui, const protocol::Protocol& p, const scene::Scene& s, std::optional<store::Answer>& answer,
            std::string& log) {
    begin_panel("##answer", kind == AnswerKind::position ? 0.62f : 0.55f);
    ImGui::PushFont(ui.heading_font());
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(question(p, s.answer).c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopFont();
    bool submit = false;
    switch (kind) {
      case AnswerKind::count: {
        if (focus) ImGui::SetKeyboardFocusHere();
        focus = false;
        ImGui::SetNextItemWidth(ui.text_px() * 6);
        const bool enter = ImGui::InputText("##count", number, sizeof number,
                                            ImGuiInputTextFlags_CharsDecimal | ImGuiInputTextFlags_EnterReturnsTrue);
        ui.name_item("Answer");
        ImGui::SameLine();
        if (ui.button(protocol::text(p, "answer.done")) || enter) {
          long long n = -1;
          const auto [end, ec] = std::from_chars(number, number + std::strlen(number), n);
          if (ec != std::errc() || end != number + std::strlen(number) || n < 0 || n > 100000) {
            problem = protocol::text(p, "answer.whole_number");
          } else {
            answer = store::Count{n};
            log = "count " + std::to_string(n);
            submit = true;
          }
        }
        break;
      }
      case AnswerKind::letter: {
        int chosen = choice_buttons(ui, letters);
        for (std::size_t i = 0; i < letters.size(); ++i)
          if (letters[i].size() == 1 && ui.input().key_pressed(Input::key_code(letters[i]))) chosen = static_cast<int>(i);
        if (chosen >= 0) {
          answer = store::Letter{letters[static_cast<std::size_t>(chosen)]};
          log = "letter " + letters[static_cast<std::size_t>(chosen)];
          submit = true;
        }
        break;
      }
      case AnswerKind::position: {
        const float side = std::min(ImGui::GetIO().DisplaySize.y * 0.7f, ImGui::GetIO().DisplaySize.x * 0.55f);
        if (auto at = floor_plan(*s.plan, s.camera.position, side, mark, protocol::text(p, "answer.start"))) mark = at;
        ui.name_item("floor plan");
        ImGui::BeginDisabled(!mark);
        if (ui.button(protocol::text(p, "answer.confirm")) || (mark && ui.input().key_pressed(GLFW_KEY_ENTER))) {
          answer = store::Position{mark->x, mark->y};
          char buf[64];
          std::snprintf(buf, sizeof buf, "position %.3f %.3f", mark->x, mark->y);
          log = buf;
          submit = true;
        }
        ImGui::EndDisabled();
        break;
      }
    }
    if (!problem.empty()) ImGui::TextColored(ImVec4(0.75f, 0.1f, 0.1f, 1), "%s", problem.c_str());
    ImGui::TextDisabled("%s", protocol::text(p, "answer.back").c_str());
    ImGui::End();
    return submit;
  }
};

}  // namespace

Result<session::TrialOutcome> WindowResponder::run_trial(const session::TrialSpec& spec) {
  console_->set_trial(&spec);
  const scene::Scene& s = *spec.scene;
  auto view = SceneView::create(s, spec.frame);
  if (!view) return view.error();
  std::unique_ptr<Texture> icon;
  if (s.kind == scene::Kind::walkthrough && !s.answer.target_kind.empty()) {
    auto t = icon_texture(s.answer.target_kind, static_cast<int>(ui_.text_px() * 4));
    if (!t) return t.error();
    icon = std::move(t.value());
  }
  AnswerInput input;
  input.kind = kind_of(s.task);
  input.letters = spec.setup->task->scene.letters;
  if (input.letters.empty()) input.letters = {"C", "K", "R", "X", "Y"};

  session::TrialOutcome out;
  out.refresh_hz = ui_.refresh_hz();
  Input& in = ui_.input();
  bool answering = false, submitted = false, started = false;
  double paused = 0, last_steer = 0;
  Clock::time_point t0{}, submitted_at{};
  const Clock::time_point screen_start = Clock::now();
  std::string log;
  in.capture_cursor((*view)->walking());
  auto since_t0 = [&] { return started ? std::chrono::duration<double>(Clock::now() - t0).count() : 0.0; };

  // "Practice" on a practice trial, "Trial k of n" where the protocol asks for a counter.
  std::string corner;
  if (spec.planned.practice && protocol_.training.practice_label)
    corner = protocol::text(protocol_, "practice.label");
  else if (!spec.planned.practice && protocol_.flow.trial_counter)
    corner = protocol::text(protocol_, "trial.counter",
                            {{"trial", std::to_string(spec.counted)}, {"trials", std::to_string(spec.counted_of)}});

  for (;;) {
    const bool showing_view = !answering && !console_->paused();
    const std::string screen = (answering ? "answer " : "trial ") + spec.planned.task;
    console_->set_screen(screen);
    Status st = ui_.frame(
        screen,
        [&]() -> Status {
          if (!showing_view) return {};
          return (*view)->draw(ui_.width(), ui_.height(), glm::vec2(in.cursor()));
        },
        [&] {
          if (console_->paused()) {
            message_panel(ui_, protocol::text(protocol_, "trial.paused_title"),
                          protocol::text(protocol_, "trial.paused_text"), protocol::text(protocol_, "trial.paused_button"));
            return;
          }
          if (!answering) {
            const double now = since_t0();
            (*view)->steer(in, now - last_steer, !ImGui::GetIO().WantCaptureMouse);
            last_steer = now;
            if (icon) find_this_panel(ui_, protocol_, *icon, s.answer.target_kind);
            if (!corner.empty()) corner_label(ui_, corner);
            const bool clicked =
                bottom_bar(ui_, protocol::text(protocol_, "trial.bar"), protocol::text(protocol_, "trial.answer"));
            if (clicked || in.key_pressed(GLFW_KEY_ENTER) || in.key_pressed(GLFW_KEY_KP_ENTER)) {
              answering = true;
              input.focus = true;
              in.capture_cursor(false);
            }
            return;
          }
          if (in.key_pressed(GLFW_KEY_ESCAPE)) {
            answering = false;
            in.capture_cursor((*view)->walking());
            return;
          }
          std::optional<store::Answer> a;
          if (input.draw(ui_, protocol_, s, a, log)) {
            out.answer = std::move(a);
            submitted = true;
            submitted_at = Clock::now();
          }
        });
    if (!st) {
      in.capture_cursor(false);
      return st.error();
    }
    if (console_->aborted()) {
      in.capture_cursor(false);
      return Error{"", 0, 0, "session", "the experimenter aborted the session (it is abandoned)", ErrorKind::conflict};
    }
    if (!started) {
      // The clock starts at the first frame actually presented.
      started = true;
      t0 = ui_.last_swap();
      out.started_at = std::chrono::system_clock::now() - std::chrono::duration_cast<std::chrono::system_clock::duration>(Clock::now() - t0);
      in.start_log(t0);
      out.frame_ms.push_back(std::chrono::duration<double, std::milli>(t0 - screen_start).count());
      out.poses.push_back((*view)->pose(0.0));
    } else if (showing_view) {
      out.frame_ms.push_back(ui_.last_frame_ms());
      out.poses.push_back((*view)->pose(std::chrono::duration<double>(ui_.last_swap() - t0).count()));
    }
    paused += console_->take_paused_s();
    if (submitted) break;
    if (spec.time_limit_s > 0 && since_t0() - paused > spec.time_limit_s) {
      submitted_at = Clock::now();  // the session's time is up: no answer
      break;
    }
  }
  in.capture_cursor(false);
  if (out.answer) in.log_answer(log);
  out.events = in.take_log();
  out.completion_s = std::max(0.0, std::chrono::duration<double>(submitted_at - t0).count() - paused);
  out.ended_at = out.started_at + std::chrono::duration_cast<std::chrono::system_clock::duration>(submitted_at - t0);
  // Keep the trial's record consistent if the clock saw frames after the answer.
  for (std::size_t i = 1; i < out.poses.size(); ++i) out.poses[i].t_s = std::max(out.poses[i].t_s, out.poses[i - 1].t_s);
  return out;
}

}  // namespace dtlab::run
