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
#include <thread>

#include <nlohmann/json.hpp>

#include "app/run/ui.h"
#include "study/common/file.h"
#include "study/common/text.h"
#include "study/render/image.h"

namespace dtlab::run {

namespace {

constexpr const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

void map_keys(ImGuiIO& io) {
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
  io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
  io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
  io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
}

std::string file_stem(const std::string& screen) {
  std::string s;
  for (char c : screen) s += (std::isalnum(static_cast<unsigned char>(c)) ? c : '-');
  return s;
}

}  // namespace

Ui::Ui(platform::Window& window, const UiOptions& options) : window_(window), options_(options) {
  if (const char* path = std::getenv("DTLAB_RUN_ITEMS")) items_path_ = path;
}

Result<std::unique_ptr<Ui>> Ui::create(platform::Window& window, const UiOptions& options) {
  std::unique_ptr<Ui> ui(new Ui(window, options));
  window.make_current();
  ui->input_ = std::make_unique<Input>(window.glfw());
  if (options.script) ui->player_ = std::make_unique<ScriptPlayer>(*options.script, *ui->input_);
  GLFWmonitor* monitor = glfwGetWindowMonitor(window.glfw());
  if (!monitor) monitor = glfwGetPrimaryMonitor();
  if (const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr; mode && mode->refreshRate > 0)
    ui->refresh_hz_ = mode->refreshRate;

  IMGUI_CHECKVERSION();
  ui->imgui_ = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini beside the study
  io.LogFilename = nullptr;
  // No keyboard navigation: it would highlight (pre-select) the first button of every page; every
  // screen has its own keys (digits for ratings, letters for T2, Enter, Escape, Space).
  io.ConfigFlags &= ~ImGuiConfigFlags_NavEnableKeyboard;
  io.BackendPlatformName = "dtlab-run";
  map_keys(io);
  // Text large enough to read at arm's length: a 28th of the window's height, 20..48 px.
  ui->text_px_ = std::clamp(static_cast<float>(window.height()) / 28.0f, 20.0f, 48.0f);
  ImFontConfig cfg;
  cfg.OversampleH = 2;
  const std::string font_file = options.font.empty() ? kFontFile : options.font;
  if (!options.font.empty() && !std::filesystem::is_regular_file(options.font))
    return Error{options.font, 0, 0, "font", "no such font file (a TrueType or OpenType file, e.g. " +
                                                 std::string(kFontFile) + ")", ErrorKind::not_found};
  if (std::filesystem::exists(font_file)) {
    // The scripts participants are written in: Latin (with Extended-A and -B: Polish, Czech,
    // Turkish, ...), Greek, Cyrillic, typographic punctuation, and every character the protocol's
    // wording uses (so a script outside these ranges still shows where the font has it).
    static const ImWchar kScripts[] = {0x0020, 0x024F, 0x0370, 0x03FF, 0x0400, 0x052F, 0x1E00, 0x1EFF,
                                       0x2000, 0x206F, 0x20A0, 0x20BF, 0x2100, 0x214F, 0};
    ImFontGlyphRangesBuilder builder;
    builder.AddRanges(kScripts);
    builder.AddText(options.glyph_text.c_str());
    builder.BuildRanges(&ui->glyph_ranges_);
    const ImWchar* ranges = ui->glyph_ranges_.Data;
    ImFont* text = io.Fonts->AddFontFromFileTTF(font_file.c_str(), ui->text_px_, &cfg, ranges);
    ui->heading_ = io.Fonts->AddFontFromFileTTF(font_file.c_str(), ui->text_px_ * 1.5f, &cfg, ranges);
    ui->small_ = io.Fonts->AddFontFromFileTTF(font_file.c_str(), std::max(14.0f, ui->text_px_ * 0.7f), &cfg, ranges);
    if (!text || !ui->heading_ || !ui->small_)
      return Error{font_file, 0, 0, "font", "the font could not be loaded (not a TrueType or OpenType file?)",
                   ErrorKind::invalid_input};
    io.Fonts->Build();
    // What the font lacks would read as '?': say so before a participant sees it.
    std::set<char32_t> reported;
    for (const char32_t c : utf8_codepoints(options.glyph_text)) {
      if (c < 0x20 || reported.count(c)) continue;
      if (c <= 0xFFFF && text->FindGlyphNoFallback(static_cast<ImWchar>(c))) continue;  // ImWchar: 16 bits here
      reported.insert(c);
      char entry[32];
      std::snprintf(entry, sizeof entry, "U+%04X", static_cast<unsigned>(c));
      ui->missing_glyphs_.push_back(entry);
    }
  } else {  // ImGui's own font, scaled (pixel-like but legible)
    cfg.SizePixels = ui->text_px_;
    io.Fonts->AddFontDefault(&cfg);
    cfg.SizePixels = ui->text_px_ * 1.5f;
    ui->heading_ = io.Fonts->AddFontDefault(&cfg);
    cfg.SizePixels = std::max(14.0f, ui->text_px_ * 0.7f);
    ui->small_ = io.Fonts->AddFontDefault(&cfg);
  }
  ImGui::StyleColorsLight();
  ImGuiStyle& style = ImGui::GetStyle();
  style.ScaleAllSizes(ui->text_px_ / 16.0f);
  style.FrameRounding = 4;
  style.WindowRounding = 6;
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    return Error{"", 0, 0, "window", "Dear ImGui's OpenGL 3 backend did not start", ErrorKind::environment};
  return ui;
}

Ui::~Ui() {
  if (!imgui_) return;
  window_.make_current();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(imgui_);
}

void Ui::name_item(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  // An item whose centre lies off the window cannot be clicked: a script must not find it either.
  const ImVec2 c((a.x + b.x) * 0.5f, (a.y + b.y) * 0.5f), display = ImGui::GetIO().DisplaySize;
  if (c.x < 0 || c.y < 0 || c.x >= display.x || c.y >= display.y) return;
  items_next_[name] = ItemBox{a.x, a.y, b.x - a.x, b.y - a.y};
}

bool Ui::button(const std::string& label, ImVec2 size) {
  const bool pressed = ImGui::Button(label.c_str(), size);
  const auto hash = label.find("##");
  name_item(hash == std::string::npos ? label : label.substr(0, hash));
  return pressed;
}

Status Ui::frame(const std::string& screen, const std::function<void()>& draw3d, const std::function<void()>& widgets) {
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
    if (Status s = player_->tick(screen_, instance_, items_, start); !s) return s;
  if (input_->ctrl() && input_->shift() && input_->key_pressed(GLFW_KEY_E)) console_shown_ = !console_shown_;

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
  if (draw3d) draw3d();
  if (widgets) widgets();
  const bool console_now = console_shown_ && console_;
  if (console_now) console_();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  items_ = std::move(items_next_);

  // The third frame of a screen has settled its layout (ImGui sizes windows on their first frames).
  if (++frames_in_screen_ == 3 && !options_.screenshots.empty()) screenshot(screen_);
  if (frames_in_screen_ == 3 && !items_path_.empty()) write_items();
  if (console_now && !options_.screenshots.empty() && !shot_.count("console")) screenshot("console");

  window_.swap_buffers();
  const Clock::time_point swapped = Clock::now();
  if (last_swap_ != Clock::time_point{}) last_frame_ms_ = std::chrono::duration<double, std::milli>(swapped - last_swap_).count();
  last_swap_ = swapped;
  // A cap at the display's rate: where vsync does not hold (a virtual display) frames would spin.
  const double cap = options_.frame_limit_hz > 0 ? options_.frame_limit_hz : refresh_hz_.value_or(60.0);
  const auto min_frame = std::chrono::duration<double>(1.0 / cap);
  const auto spent = Clock::now() - start;
  if (spent < min_frame) std::this_thread::sleep_for(min_frame - spent);
  return {};
}

void Ui::write_items() const {
  nlohmann::json j{{"screen", screen_}, {"instance", instance_}, {"items", nlohmann::json::object()}};
  for (const auto& [name, b] : items_) j["items"][name] = {b.x, b.y, b.w, b.h};
  write_file_atomically(items_path_, [&](std::ostream& out) -> Status {
    out << j.dump() << "\n";
    return {};
  });
}

void Ui::screenshot(const std::string& name) {
  if (!shot_.insert(name).second) return;
  const int w = window_.width(), h = window_.height();
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
