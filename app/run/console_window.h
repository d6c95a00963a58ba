// The experimenter console's own window (`dtlab run --console-monitor N`): a
// second GLFW window on monitor N with its own GL context, its own Dear ImGui
// context (detail/imgui_setup.h: the backend's state lives in each context's
// IO, so two contexts each with their own backend instance work side by side)
// and its own run::Input, fed by that window's GLFW callbacks and by a
// script's `window console` steps. Ui draws it after the participant's buffer
// swap, in the time left before the participant's next frame.
// Guarantees: frame() leaves the participant's GL and ImGui contexts current;
// closing the window is ignored (the session goes on); the keyboard goes back
// to the participant's window when the pointer leaves the console's and none
// of its fields is being typed in. Never: draws in the participant's window.
#pragma once
#include <chrono>
#include <functional>
#include <cstdint>
#include <memory>
#include <vector>

#include "app/platform/gl_context.h"
#include "app/run/detail/imgui_setup.h"
#include "app/run/input.h"
#include "study/common/error.h"

namespace dtlab::run {

class ConsoleWindow {
 public:
  // Opens the window on `monitor` (an index into platform::monitors()), which must not be the
  // participant's. Errors: no such monitor (the message lists them), no GL 3.3, no backend.
  // Its text in `font` (the participant's: notes may be typed in the participant's language).
  static Result<std::unique_ptr<ConsoleWindow>> open(int monitor, platform::Window& participant,
                                                     ImGuiContext* participant_imgui, const detail::FontSpec& font);
  ~ConsoleWindow();
  ConsoleWindow(const ConsoleWindow&) = delete;
  ConsoleWindow& operator=(const ConsoleWindow&) = delete;

  Input& input() { return *input_; }
  // The experimenter's Ctrl+Shift+E in the participant's window: the console's window gets the
  // keyboard and the pointer (lent by the participant's input, free of a WALKTHROUGH capture);
  // both go back when the pointer leaves the console's window (or the participant's is clicked).
  void take_keyboard_and_pointer(Input& participant_input);
  ImFont* small_font() const { return imgui_.small; }
  float text_px() const { return text_px_; }

  // A frame is due: the last one is at least 1/kMaxHz old, and either `budget` (the time left
  // before the participant's next frame) holds one at the last frame's cost, or the last one is
  // older than kMaxAgeS (the console stays alive when the participant's frames use all the time).
  bool due(Clock::time_point now, std::chrono::duration<double> budget) const;
  // One frame: its ImGui context current, its input fed to ImGui, draw() inside the ImGui frame;
  // when the picture differs from the one on screen (or the window system lost it): its GL context
  // current, the picture drawn, before_swap(), the swap (never synchronised to the display: the
  // participant's swap is). Then the participant's contexts are current again.
  void frame(const std::function<void()>& draw, const std::function<void()>& before_swap);
  int width() const { return width_; }  // framebuffer pixels
  int height() const { return height_; }

  static constexpr double kMaxHz = 30;    // console frames a second at most
  static constexpr double kMaxAgeS = 0.2; // a console frame at least this often

 private:
  ConsoleWindow(platform::Window& participant, ImGuiContext* participant_imgui)
      : participant_(participant), participant_imgui_(participant_imgui) {}
  void return_keyboard();
  bool changed(const ImDrawData& d, int fw, int fh);  // the picture differs from the one presented last

  platform::Window& participant_;
  ImGuiContext* participant_imgui_;
  Input* lender_ = nullptr;  // the participant's input while it lends the pointer here
  std::unique_ptr<platform::Window> window_;
  std::unique_ptr<Input> input_;
  ImVector<ImWchar> glyph_ranges_;  // its font atlas's ranges; outlive its ImGui context (destroyed first)
  detail::ImGuiSetup imgui_;
  float text_px_ = 24;
  int size_x_ = 0, size_y_ = 0, width_ = 0, height_ = 0;  // screen points; framebuffer pixels (fixed size)
  Clock::time_point last_frame_{};
  std::chrono::duration<double> last_cost_{0};
  bool had_keyboard_ = false;  // the console window had the keyboard at its last frame
  std::vector<char> shown_;    // the presented picture's draw data (vertices, indices, commands)
  bool refresh_ = true;        // present the next frame whatever it shows
};

}  // namespace dtlab::run
