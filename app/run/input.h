// The participant window's input, from one place. GLFW's callbacks call the
// on_*() entry points, and so does the script player (--script): the app and
// Dear ImGui read only this state, so they cannot tell a scripted event from
// a person's. Each frame: new_frame() clears the per-frame edges and deltas,
// the events of the frame arrive (glfwPollEvents, the script), then the
// screens read the state and feed_imgui() hands it to ImGui. Every event is
// also logged with its steady-clock time for the trial record.
// Never: polls GLFW for input state behind this class's back.
#pragma once
#include <array>
#include <chrono>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "study/store/store.h"

struct GLFWwindow;

namespace dtlab::run {

using Clock = std::chrono::steady_clock;

// The input events of one trial, kept in memory: appending is all a frame pays for logging;
// the store writes the whole log with the trial's result in one transaction when it ends.
class EventLog {
 public:
  void start(Clock::time_point origin);  // a new log; times are seconds since `origin` (>= 0)
  void add(store::InputEvent::Kind kind, std::string detail, double x, double y);  // no-op unless started
  std::vector<store::InputEvent> take();  // hands the events over and stops logging
  bool active() const { return active_; }

 private:
  bool active_ = false;
  Clock::time_point origin_{};
  std::vector<store::InputEvent> events_;
};

class Input {
 public:
  // Installs GLFW callbacks on `window` that forward here; `window` outlives this object. A null
  // window installs nothing: events arrive only through the entry points below.
  explicit Input(GLFWwindow* window);
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // --- the entry points (GLFW key, button and action codes) -----------------------------
  void on_key(int key, int action, int mods);
  void on_char(unsigned codepoint);
  void on_mouse_button(int button, int action, int mods);
  void on_cursor(double x, double y);          // window coordinates (screen points), origin top-left
  void on_scroll(double dx, double dy);
  void on_focus(bool focused);                 // the window got or lost the keyboard
  void on_enter(bool inside);                  // the pointer entered or left the window

  // --- per frame ---------------------------------------------------------------------------
  void new_frame();                            // before the frame's events arrive
  void feed_imgui(float delta_s) const;        // after they arrived: ImGuiIO gets mouse, keys, text

  // --- state -------------------------------------------------------------------------------
  bool key_down(int key) const;
  bool key_pressed(int key) const;             // went down during this frame
  bool button_down(int button) const;
  bool button_pressed(int button) const;       // went down during this frame
  bool button_released(int button) const;      // went up during this frame
  glm::dvec2 cursor() const { return cursor_; }
  glm::dvec2 cursor_delta() const { return delta_; }  // movement during this frame
  glm::dvec2 scroll() const { return scroll_; }       // during this frame
  bool ctrl() const;
  bool shift() const;
  bool focused() const { return focused_; }    // the window has the keyboard (as its events said)
  bool hovered() const { return hovered_; }    // the pointer is over the window (as its events said)
  // This frame's press of `key` is not one for the screens: key_pressed() is false and ImGui sees no
  // new press (the experimenter's chords; the key still reads as down while held).
  void swallow_press(int key);

  // Cursor capture (WALKTHROUGH turning): hidden and unbounded while captured.
  void capture_cursor(bool on);
  bool cursor_captured() const { return captured_; }
  // The pointer lent to another window (the console's, Ctrl+Shift+E with --console-monitor): free
  // even while captured, and its motion turns nothing here, until lend_pointer(false) or a button
  // pressed in this window takes it back.
  void lend_pointer(bool on);
  bool pointer_lent() const { return lent_; }

  // --- the event log ------------------------------------------------------------------------
  // Starts a new log at `origin` (a trial's start); events from then on are kept with t_s
  // relative to it. take_log() hands them over and stops logging.
  void start_log(Clock::time_point origin);
  std::vector<store::InputEvent> take_log();
  // Records an event that is not an input (the answer given, e.g. "count 12").
  void log_answer(const std::string& detail);

  // The GLFW name of a key ("Up", "Enter", "A", ...) and back; -1 for an unknown name.
  static std::string key_name(int key);
  static int key_code(const std::string& name);

 private:

  GLFWwindow* window_;
  std::array<bool, 512> keys_{}, pressed_{};
  std::array<bool, 8> buttons_{}, button_pressed_{}, button_released_{};
  std::vector<unsigned> chars_;  // typed this frame
  glm::dvec2 cursor_{0.0}, delta_{0.0}, scroll_{0.0};
  bool have_cursor_ = false;
  bool captured_ = false;
  bool lent_ = false;
  bool focused_ = false, hovered_ = false;
  bool rebase_ = false;  // the next cursor position adds no motion (the pointer came back)
  EventLog log_;
};

}  // namespace dtlab::run
