// The experimenter console (console.h).
#include <imgui.h>
#include <imgui_internal.h>

#include <cstdio>

#include "app/run/console.h"
#include "study/store/read.h"

namespace dtlab::run {

namespace {

std::string answer_text(const scene::Answer& a) {
  switch (a.task) {
    case scene::Task::T1: return "count " + std::to_string(a.count);
    case scene::Task::T2: return std::string("letter ") + a.letter;
    case scene::Task::T3: {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s at x %.1f, z %.1f", a.target_kind.c_str(), a.position.x, a.position.y);
      return buf;
    }
    case scene::Task::T4: return "count " + std::to_string(a.count) + " of " + a.target_kind;
  }
  return "?";
}

}  // namespace

Console::Console(Ui& ui, store::Store& store, std::string participant, std::string experimenter)
    : ui_(ui), store_(store), participant_(std::move(participant)), experimenter_(std::move(experimenter)) {}

void Console::set_session(const store::Session& session, int planned) {
  session_ = session;
  planned_ = planned;
  progress_stale_ = true;
}

void Console::set_trial(const session::TrialSpec* trial) {
  trial_ = trial;
  progress_stale_ = true;
}

void Console::read_progress() {
  progress_stale_ = false;
  recorded_.reset();
  positions_.clear();
  if (session_)
    if (auto now = store_.session(participant_)) recorded_ = now->recorded;
  if (auto rows = store_.read().trials(participant_))
    for (const auto& r : *rows) positions_.push_back(r.planned.position);
}

double Console::take_paused_s() {
  const double s = paused_s_;
  paused_s_ = 0;
  return s;
}

bool Console::take_end_training() {
  const bool e = end_training_;
  end_training_ = false;
  return e;
}

void Console::pause(bool on) {
  if (on == paused_) return;
  if (on) {
    paused_ = true;
    pause_steady_ = Clock::now();
    pause_wall_ = std::chrono::system_clock::now();
    status_ = "Paused.";
    return;
  }
  paused_ = false;
  paused_s_ += std::chrono::duration<double>(Clock::now() - pause_steady_).count();
  if (!session_) return;
  const std::optional<int> position = trial_ ? std::optional<int>(trial_->planned.position) : std::nullopt;
  Status st = store_.record_pause(*session_, position, pause_wall_, std::chrono::system_clock::now());
  status_ = st ? "Resumed; the pause is recorded." : "Could not record the pause: " + st.error().to_string();
}

// The console's ImGui window: all of its own window, or a panel over the participant's screen.
void Console::begin_window(bool own_window) {
  ImGuiIO& io = ImGui::GetIO();
  if (own_window) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(io.DisplaySize);
    ImGui::Begin("Experimenter console", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove);
    return;
  }
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.04f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x * 0.7f, io.DisplaySize.y * 0.8f), ImGuiCond_Appearing);
  ImGui::SetNextWindowBgAlpha(0.96f);
  ImGui::Begin("Experimenter console (Ctrl+Shift+E hides it)", nullptr, ImGuiWindowFlags_NoCollapse);
  // Above every participant panel, also one that appears later (the pause message does, and
  // ImGui puts an appearing window in front): the experimenter's clicks must reach the console.
  ImGui::BringWindowToDisplayFront(ImGui::GetCurrentWindow());
}

void Console::draw_progress(bool own_window) {
  ImGui::Text("Participant %s", participant_.c_str());
  if (session_ && recorded_)
    ImGui::Text("Session %lld: %d of %d trials recorded", static_cast<long long>(session_->id), *recorded_, planned_);
  ImGui::Text("Screen: %s", screen_.c_str());
  if (!trial_) return;
  const auto& t = trial_->planned;
  std::string levels;
  for (const auto& [f, l] : t.levels) levels += (levels.empty() ? "" : ", ") + f + " " + l;
  ImGui::Separator();
  ImGui::Text("Trial %d (block %d): task %s, repetition %d%s", t.position, t.block, t.task.c_str(), t.trial,
              t.practice ? ", practice" : "");
  ImGui::Text("Condition: %s; method %s", levels.c_str(), t.method.c_str());
  // The trial's truth: in the console's own window always; over the participant's screen only
  // while the experimenter holds the chord (the participant may be looking).
  if (own_window || ui_.answer_key_held()) {
    ImGui::Text("Answer key: %s", answer_text(trial_->scene->answer).c_str());
    ui_.name_item("Answer key");
  } else {
    ImGui::TextDisabled("Answer key hidden: hold Ctrl+Shift+K to show the answer key");
    ui_.name_item("Answer key hidden");
  }
}

// Invalid trials: the current one and every recorded one.
void Console::draw_invalid() {
  ImGui::TextUnformatted("Mark a trial invalid (it is kept, and left out of the analysis):");
  std::vector<int> positions = positions_;
  if (trial_ && (positions.empty() || positions.back() != trial_->planned.position))
    positions.push_back(trial_->planned.position);
  for (int p : positions) {
    ImGui::PushID(p);
    if (ui_.button("Trial " + std::to_string(p) + " invalid...")) {
      invalid_position_ = p;
      reason_[0] = '\0';
    }
    ImGui::PopID();
    if (p % 6 != 0 && p != positions.back()) ImGui::SameLine();
  }
  if (invalid_position_ <= 0) return;
  ImGui::Text("Why is trial %d invalid?", invalid_position_);
  ImGui::InputText("##reason", reason_, sizeof reason_);
  ui_.name_item("Reason");
  if (ui_.button("Record as invalid")) {
    Status st = store_.exclude(participant_, invalid_position_, reason_, experimenter_);
    status_ = st ? "Trial " + std::to_string(invalid_position_) + " marked invalid." : st.error().to_string();
    if (st) invalid_position_ = 0;
  }
}

void Console::draw_note() {
  ImGui::TextUnformatted("Note:");
  ImGui::InputTextMultiline("##note", note_, sizeof note_, ImVec2(-1, ui_.text_px() * 3));
  ui_.name_item("Note");
  if (ui_.button("Save note")) {
    const std::optional<int> position = trial_ ? std::optional<int>(trial_->planned.position) : std::nullopt;
    Status st = store_.add_note(participant_, position, experimenter_, note_);
    status_ = st ? "Note saved." : st.error().to_string();
    if (st) note_[0] = '\0';
  }
}

void Console::draw_abort() {
  if (!confirm_abort_) {
    if (ui_.button("Abort the session...")) confirm_abort_ = true;
    return;
  }
  ImGui::TextUnformatted("The session is marked abandoned and its order row freed; recorded trials stay.");
  if (ui_.button("Abort: the session is abandoned")) {
    Status st = store_.release(participant_);
    if (st) {
      store_.add_note(participant_, trial_ ? std::optional<int>(trial_->planned.position) : std::nullopt,
                      experimenter_, "session aborted from the console");
      aborted_ = true;
      trial_ = nullptr;  // the trial ends with the session (its spec with it): the end screen has none
      // The overlay closes: nothing is left to act on in it, and the end screen's Close button must
      // not lie under it.
      ui_.show_console(false);
      status_ = "Session abandoned.";
    } else {
      status_ = st.error().to_string();
    }
  }
  ImGui::SameLine();
  if (ui_.button("Keep going")) confirm_abort_ = false;
}

void Console::draw() {
  const bool own_window = ui_.drawing_console_window();
  begin_window(own_window);
  if (progress_stale_) read_progress();
  ImGui::PushFont(ui_.small_font());
  draw_progress(own_window);
  if (!aborted_) {  // after an abort nothing is left to act on (the end screen is up)
    ImGui::Separator();
    if (ui_.button(paused_ ? "Resume" : "Pause")) pause(!paused_);
    ImGui::SameLine();
    if (ui_.button("End training")) end_training_ = true;
    ImGui::Separator();
    draw_invalid();
    ImGui::Separator();
    draw_note();
    ImGui::Separator();
    draw_abort();
  } else {
    ImGui::Separator();
  }
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
  ImGui::PopFont();
  ImGui::End();
}

}  // namespace dtlab::run
