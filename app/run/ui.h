// The participant window's frame loop: Dear ImGui (its OpenGL3 backend;
// input comes from run::Input, never from GLFW directly) over the
// renderer's 3D view, with large text for reading at arm's length, a
// registry of named UI items (for scripts and tests), the experimenter
// console (an overlay on Ctrl+Shift+E, or its own window on another monitor,
// console_window.h), the script player and screenshots.
// Guarantees: every frame is one call of frame(); the time of each buffer
// swap is kept (trial clocks start at the first one), and the console's own
// window is drawn only after that swap; the console chords (Ctrl+Shift+E,
// Ctrl+Shift+K) never reach a participant screen as key presses; the GL
// state the renderer and ImGui's backend leave is theirs to restore. Never:
// writes to the study database (screens and the console do, through the store).
#pragma once
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <imgui.h>

#include "app/platform/gl_context.h"
#include "app/run/input.h"
#include "app/run/script.h"
#include "study/common/error.h"

namespace dtlab::run {

struct UiOptions {
  std::string screenshots;        // directory for one PNG per distinct screen; "" = none
  std::string font;               // a TrueType/OpenType file; "" = DejaVu Sans (Latin, Greek, Cyrillic)
  std::string glyph_text;         // text whose every character the font atlas must hold (the protocol's wording)
  const Script* script = nullptr; // scripted input, or none
  double frame_limit_hz = 0;      // 0: the display's refresh rate (a cap when vsync does not hold)
  int console_monitor = -1;       // >= 0: the console in its own window on that monitor; -1: an overlay
};

class ConsoleWindow;

class Ui {
 public:
  static Result<std::unique_ptr<Ui>> create(platform::Window& window, const UiOptions& options);
  ~Ui();
  Ui(const Ui&) = delete;
  Ui& operator=(const Ui&) = delete;

  Input& input() { return *input_; }
  platform::Window& window() { return window_; }
  int width() const { return window_.width(); }    // framebuffer pixels
  int height() const { return window_.height(); }
  std::optional<double> refresh_hz() const { return refresh_hz_; }  // the monitor's, when it says

  // One frame of screen `screen` (e.g. "trial T1"): the frame's events, then draw3d() (the 3D
  // view, into the default framebuffer), then widgets() (ImGui), the console if shown, and the
  // buffer swap. A new screen id, or new_instance(), restarts the script's section for it.
  // Errors: the window was closed (kind conflict: the session stays resumable), a script step
  // failed, draw3d's Error (the renderer's: the frame ends there, unswapped).
  Status frame(const std::string& screen, const std::function<Status()>& draw3d, const std::function<void()>& widgets);
  // Scripted: the screen's section has played out and the screen is still up (start.cpp turns a
  // refusal there into an error instead of waiting for a person forever). Its section's line.
  bool script_played_out() const { return player_ && player_->played_out(); }
  int script_section_line() const { return player_ ? player_->section_line() : 0; }
  const Script* script() const { return options_.script; }
  void new_instance() { ++instance_; }                // the next frame starts a new instance of the same screen
  Clock::time_point last_swap() const { return last_swap_; }
  double last_frame_ms() const { return last_frame_ms_; }  // between the last two swaps

  // Named items: registers the last ImGui item's box under `name` (the script's click_item), if its
  // centre lies inside the window.
  void name_item(const std::string& name);
  bool button(const std::string& label, ImVec2 size = ImVec2(0, 0));  // ImGui::Button, named by its label
  ImFont* heading_font() const { return heading_; }
  ImFont* small_font() const;  // the experimenter's screens (start, console): read at a desk
  float text_px() const { return text_px_; }
  // Characters of UiOptions::glyph_text the font has no glyph for (ImGui would draw '?'), as
  // "U+XXXX" entries; empty when the font covers the protocol's wording.
  const std::vector<std::string>& missing_glyphs() const { return missing_glyphs_; }

  // The experimenter console. In its own window (UiOptions::console_monitor) it is drawn there
  // after every participant frame (as often as the participant's frames leave time for); else it is
  // drawn over every screen while shown (toggled by Ctrl+Shift+E).
  void set_console(std::function<void()> draw) { console_ = std::move(draw); }
  bool console_shown() const { return console_window_ != nullptr || console_shown_; }
  void show_console(bool on) { console_shown_ = on; }  // the overlay's state (no effect with its own window)
  // Drawing now in the console's own window (inside the console's draw function).
  bool drawing_console_window() const { return naming_ == &console_items_next_; }
  // The experimenter holds Ctrl+Shift+K in the participant's window: the overlay may show the answer key.
  bool answer_key_held() const;

 private:
  Ui(platform::Window& window, const UiOptions& options);
  void console_chords();     // Ctrl+Shift+E and Ctrl+Shift+K: the experimenter's, never a participant screen's
  void console_frame(Clock::time_point frame_start, std::chrono::duration<double> min_frame);
  void screenshot(const std::string& name, int w, int h);  // the current GL context's back buffer (w x h pixels)
  void write_items() const;  // $DTLAB_RUN_ITEMS: the screen and its named items' boxes, as JSON (tests drive real X events by them)
  // $DTLAB_RUN_ITEMS_LOG: one JSON line whenever the names of a window's items change (tests read what
  // each window showed, frame by frame, from it).
  void log_items(const char* window, const ItemBoxes& items, std::set<std::string>& last);

  platform::Window& window_;
  UiOptions options_;
  std::unique_ptr<Input> input_;
  std::unique_ptr<ScriptPlayer> player_;
  ImGuiContext* imgui_ = nullptr;
  ImFont* heading_ = nullptr;
  ImFont* small_ = nullptr;
  float text_px_ = 24;
  ImVector<ImWchar> glyph_ranges_;  // the atlas's ranges; must outlive the atlas
  std::vector<std::string> missing_glyphs_;
  std::optional<double> refresh_hz_;
  std::string screen_;
  std::uint64_t instance_ = 0, played_instance_ = 0;  // the screen instance now; the one frames run in
  int frames_in_screen_ = 0;
  ItemBoxes items_, items_next_;
  ItemBoxes console_items_, console_items_next_;  // the console window's
  ItemBoxes* naming_ = &items_next_;              // where name_item() registers (the window being drawn)
  std::set<std::string> shot_;      // screens already saved
  std::string items_path_;          // $DTLAB_RUN_ITEMS, or ""
  std::string items_log_path_;      // $DTLAB_RUN_ITEMS_LOG, or ""
  std::set<std::string> logged_, console_logged_;  // the item names of each window's last log line
  int shots_ = 0;
  std::function<void()> console_;
  bool console_shown_ = false;
  std::unique_ptr<ConsoleWindow> console_window_;
  Clock::time_point last_swap_{}, frame_start_{};
  double last_frame_ms_ = 0;
};

}  // namespace dtlab::run
