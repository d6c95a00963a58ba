// The frame loop of the participant window (ui.h).
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/run/console_window.h"
#include "app/run/detail/imgui_setup.h"
#include "app/run/ui.h"
#include "study/common/file.h"
#include "study/render/image.h"

namespace dtlab::run {

namespace {

std::string file_stem(const std::string& screen) {
  std::string s;
  for (char c : screen) s += (std::isalnum(static_cast<unsigned char>(c)) ? c : '-');
  return s;
}

// What the console's own window shows while no session runs (start and end screens).
void console_idle(Ui& ui) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("Experimenter console", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove);
  ImGui::PushFont(ui.small_font());
  ImGui::TextWrapped("Experimenter console. It shows the session from its first screen on; until then the "
                     "start screen is in the participant's window.");
  ImGui::PopFont();
  ImGui::End();
}

}  // namespace

Ui::Ui(platform::Window& window, const UiOptions& options) : window_(window), options_(options) {
  if (const char* path = std::getenv("DTLAB_RUN_ITEMS")) items_path_ = path;
  if (const char* path = std::getenv("DTLAB_RUN_ITEMS_LOG")) items_log_path_ = path;
}

Result<std::unique_ptr<Ui>> Ui::create(platform::Window& window, const UiOptions& options) {
  std::unique_ptr<Ui> ui(new Ui(window, options));
  window.make_current();
  ui->input_ = std::make_unique<Input>(window.glfw());
  GLFWmonitor* monitor = glfwGetWindowMonitor(window.glfw());
  if (!monitor) monitor = glfwGetPrimaryMonitor();
  if (const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr; mode && mode->refreshRate > 0)
    ui->refresh_hz_ = mode->refreshRate;
  // Text large enough to read at arm's length: a 28th of the window's height, 20..48 px.
  ui->text_px_ = std::clamp(static_cast<float>(window.height()) / 28.0f, 20.0f, 48.0f);
  auto imgui = detail::create_imgui(ui->text_px_, detail::FontSpec{options.font, options.glyph_text}, ui->glyph_ranges_);
  if (!imgui) return imgui.error();
  ui->imgui_ = imgui->context;
  ui->heading_ = imgui->heading;
  ui->small_ = imgui->small;
  ui->missing_glyphs_ = std::move(imgui->missing_glyphs);
  if (options.console_monitor >= 0) {
    auto console = ConsoleWindow::open(options.console_monitor, window, ui->imgui_,
                                       detail::FontSpec{options.font, options.glyph_text});
    if (!console) return console.error();
    ui->console_window_ = std::move(console.value());
  }
  if (options.script)
    ui->player_ = std::make_unique<ScriptPlayer>(*options.script, *ui->input_,
                                                 ui->console_window_ ? &ui->console_window_->input() : nullptr);
  return ui;
}

Ui::~Ui() {
  player_.reset();
  console_window_.reset();
  if (!imgui_) return;
  window_.make_current();
  detail::destroy_imgui(imgui_);
}

ImFont* Ui::small_font() const {
  return drawing_console_window() ? console_window_->small_font() : small_;
}

void Ui::name_item(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  // An item whose centre lies off the window cannot be clicked: a script must not find it either.
  const ImVec2 c((a.x + b.x) * 0.5f, (a.y + b.y) * 0.5f), display = ImGui::GetIO().DisplaySize;
  if (c.x < 0 || c.y < 0 || c.x >= display.x || c.y >= display.y) return;
  (*naming_)[name] = ItemBox{a.x, a.y, b.x - a.x, b.y - a.y};
}

bool Ui::button(const std::string& label, ImVec2 size) {
  const bool pressed = ImGui::Button(label.c_str(), size);
  const auto hash = label.find("##");
  name_item(hash == std::string::npos ? label : label.substr(0, hash));
  return pressed;
}

bool Ui::answer_key_held() const {
  return input_->ctrl() && input_->shift() && input_->key_down(GLFW_KEY_K);
}

void Ui::console_chords() {
  if (!input_->ctrl() || !input_->shift()) return;
  if (input_->key_pressed(GLFW_KEY_E)) {
    if (console_window_) console_window_->take_keyboard_and_pointer(*input_);  // never an overlay then
    else console_shown_ = !console_shown_;
  }
  // A chord's letter is the experimenter's: no screen may read it as an answer (K is a T2 letter).
  input_->swallow_press(GLFW_KEY_E);
  input_->swallow_press(GLFW_KEY_K);
}

Status Ui::frame(const std::string& screen, const std::function<Status()>& draw3d, const std::function<void()>& widgets) {
  const Clock::time_point start = Clock::now();
  const float dt = frame_start_ == Clock::time_point{} ? 1.0f / 60.0f
                                                       : std::chrono::duration<float>(start - frame_start_).count();
  frame_start_ = start;
  if (screen != screen_ || instance_ != played_instance_) {
    if (screen != screen_) ++instance_;
    screen_ = screen;
    played_instance_ = instance_;
    frames_in_screen_ = 0;
    items_.clear();  // the last screen's items are gone: a script must not click them
    if (player_) player_->leave();
  }
  window_.make_current();
  input_->new_frame();
  window_.poll_events();
  if (window_.should_close())
    return Error{"", 0, 0, "window",
                 "the window was closed; every finished trial is saved and running dtlab run again resumes the session",
                 ErrorKind::conflict};
  // A screen's script section starts once the screen has been presented twice: its layout has
  // settled and its focus requests have taken effect, as when a person starts to act on it.
  if (player_ && frames_in_screen_ >= 2)
    if (Status s = player_->tick(screen_, instance_, items_, console_items_, start); !s) return s;
  console_chords();

  ImGuiIO& io = ImGui::GetIO();
  int ww = 0, wh = 0;
  glfwGetWindowSize(window_.glfw(), &ww, &wh);
  const int fw = window_.width(), fh = window_.height();
  io.DisplaySize = ImVec2(static_cast<float>(ww), static_cast<float>(wh));
  if (ww > 0 && wh > 0)
    io.DisplayFramebufferScale = ImVec2(static_cast<float>(fw) / static_cast<float>(ww), static_cast<float>(fh) / static_cast<float>(wh));
  ImGui_ImplOpenGL3_NewFrame();
  input_->feed_imgui(dt);
  ImGui::NewFrame();
  items_next_.clear();

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fw, fh);
  glClearColor(0.93f, 0.93f, 0.93f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  if (draw3d)
    if (Status drawn = draw3d(); !drawn) {
      ImGui::EndFrame();  // the next frame (an end screen) starts clean
      return drawn;
    }
  if (widgets) widgets();
  // Over the participant's screen only without a console window: there, never.
  const bool overlay = !console_window_ && console_shown_ && console_;
  if (overlay) console_();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  items_ = std::move(items_next_);
  if (!items_log_path_.empty()) log_items("participant", items_, logged_);

  // The third frame of a screen has settled its layout (ImGui sizes windows on their first frames).
  if (++frames_in_screen_ == 3 && !options_.screenshots.empty()) screenshot(screen_, fw, fh);
  if (frames_in_screen_ == 3 && !items_path_.empty()) write_items();
  if (overlay && !options_.screenshots.empty() && !shot_.count("console")) screenshot("console", fw, fh);

  window_.swap_buffers();
  const Clock::time_point swapped = Clock::now();
  if (last_swap_ != Clock::time_point{}) last_frame_ms_ = std::chrono::duration<double, std::milli>(swapped - last_swap_).count();
  last_swap_ = swapped;
  // A cap at the display's rate: where vsync does not hold (a virtual display) frames would spin.
  const double cap = options_.frame_limit_hz > 0 ? options_.frame_limit_hz : refresh_hz_.value_or(60.0);
  const auto min_frame = std::chrono::duration<double>(1.0 / cap);
  if (console_window_) console_frame(start, min_frame);
  const auto spent = Clock::now() - start;
  if (spent < min_frame) std::this_thread::sleep_for(min_frame - spent);
  return {};
}

// The console's own window, after the participant's swap: in the time left before the participant's
// next frame, so the participant's frames keep their pace (ConsoleWindow::due).
void Ui::console_frame(Clock::time_point frame_start, std::chrono::duration<double> min_frame) {
  const Clock::time_point now = Clock::now();
  if (!console_window_->due(now, min_frame - (now - frame_start))) return;
  console_items_next_.clear();
  naming_ = &console_items_next_;
  // The gallery's picture of the console window: its first frame that shows an answer key (presented,
  // since the frame before showed none; the console's window has a fixed layout from its first frame).
  const bool shoot = !options_.screenshots.empty() && !shot_.count("console-window");
  console_window_->frame(
      [&] {
        if (console_) console_();
        else console_idle(*this);
      },
      [&] {
        if (shoot && console_items_next_.count("Answer key"))
          screenshot("console-window", console_window_->width(), console_window_->height());
      });
  naming_ = &items_next_;
  console_items_ = std::move(console_items_next_);
  if (player_) player_->console_drew();
  if (!items_log_path_.empty()) log_items("console", console_items_, console_logged_);
}

void Ui::log_items(const char* window, const ItemBoxes& items, std::set<std::string>& last) {
  std::set<std::string> names;
  for (const auto& [name, box] : items) names.insert(name);
  if (names == last) return;
  last = names;
  std::ofstream out(items_log_path_, std::ios::app);
  out << nlohmann::json{{"window", window}, {"screen", screen_}, {"items", names}}.dump() << "\n";
}

void Ui::write_items() const {
  nlohmann::json j{{"screen", screen_}, {"instance", instance_}, {"items", nlohmann::json::object()}};
  for (const auto& [name, b] : items_) j["items"][name] = {b.x, b.y, b.w, b.h};
  write_file_atomically(items_path_, [&](std::ostream& out) -> Status {
    out << j.dump() << "\n";
    return {};
  });
}

void Ui::screenshot(const std::string& name, int w, int h) {
  if (!shot_.insert(name).second) return;
  render::Image img;
  img.width = w;
  img.height = h;
  img.rgba.resize(static_cast<std::size_t>(w) * h * 4);
  std::vector<std::uint8_t> rows(img.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  for (int y = 0; y < h; ++y)  // GL's rows start at the bottom
    std::copy_n(rows.data() + static_cast<std::size_t>(h - 1 - y) * w * 4, static_cast<std::size_t>(w) * 4,
                img.rgba.data() + static_cast<std::size_t>(y) * w * 4);
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%02d-", ++shots_);
  std::filesystem::create_directories(options_.screenshots);
  render::write_png(img, (std::filesystem::path(options_.screenshots) / (prefix + file_stem(name) + ".png")).string());
}

}  // namespace dtlab::run
