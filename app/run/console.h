// The experimenter console of `dtlab run`: with --console-monitor N its own
// window on that monitor (console_window.h), else a panel over the
// participant's screen toggled by Ctrl+Shift+E (a chord nobody presses by
// accident). It shows progress, the current trial with its condition and
// answer key, and lets the experimenter pause and resume (the pause is stored
// with its length, and paused time is not completion time), mark the current
// or a past trial invalid with a reason, write notes, end training, and abort
// the session as abandoned. Every action is written through the store at once
// (exclusions, notes, pauses, release); nothing is only shown. Never: shows
// the answer key over the participant's screen unless the experimenter holds
// Ctrl+Shift+K (its own window, on another monitor, always shows it).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "app/run/ui.h"
#include "study/session/session.h"
#include "study/store/store.h"

namespace dtlab::run {

class Console {
 public:
  Console(Ui& ui, store::Store& store, std::string participant, std::string experimenter);

  void set_session(const store::Session& session, int planned);
  void set_trial(const session::TrialSpec* trial);  // the trial running now, or none
  void set_screen(std::string what) { screen_ = std::move(what); }    // what the participant sees now

  void draw();  // the panel, in the window Ui draws (call inside an ImGui frame)

  bool paused() const { return paused_; }
  // Seconds the session was paused since the last call (a trial clock subtracts them).
  double take_paused_s();
  bool take_end_training();  // the experimenter ended the training (once)
  bool aborted() const { return aborted_; }

 private:
  void pause(bool on);
  void begin_window(bool own_window);   // ImGui::Begin of the console, in its own window or as the overlay
  void draw_progress(bool own_window);  // who, where, the trial and its answer key (or that it is hidden)
  void draw_invalid();                  // "Trial N invalid..." and the reason field
  void draw_note();
  void draw_abort();                    // with its confirmation
  void read_progress();  // the recorded trials, from the store (when the session or its trial changed)

  Ui& ui_;
  store::Store& store_;
  std::string participant_, experimenter_;
  std::optional<store::Session> session_;
  int planned_ = 0;
  const session::TrialSpec* trial_ = nullptr;
  // Progress as the store has it, read again only when it may have changed (set_session, set_trial):
  // the console draws up to 30 times a second beside the participant's frames.
  bool progress_stale_ = true;
  std::optional<int> recorded_;   // trials recorded in the session (none before it starts)
  std::vector<int> positions_;    // positions of the recorded trials
  std::string screen_;
  bool paused_ = false;
  Clock::time_point pause_steady_{};
  std::chrono::system_clock::time_point pause_wall_{};
  double paused_s_ = 0;
  bool end_training_ = false;
  bool aborted_ = false, confirm_abort_ = false;
  int invalid_position_ = 0;    // the trial whose invalid-reason field is open (0 = none)
  char reason_[256] = {};
  char note_[1024] = {};
  std::string status_;          // the last action's outcome (or the store's error)
};

}  // namespace dtlab::run
