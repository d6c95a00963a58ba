// The experimenter console's own window (console_window.h).
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>

#include "app/run/console_window.h"

namespace dtlab::run {

namespace {
// The one console window (GLFW's refresh callback has no user data of its own: the window's user
// pointer is its Input's).
ConsoleWindow* g_console = nullptr;
}  // namespace

Result<std::unique_ptr<ConsoleWindow>> ConsoleWindow::open(int monitor, platform::Window& participant,
                                                           ImGuiContext* participant_imgui,
                                                           const detail::FontSpec& font) {
  const std::vector<platform::Monitor> monitors = platform::monitors();
  if (monitor < 0 || monitor >= static_cast<int>(monitors.size()))
    return Error{"", 0, 0, "--console-monitor",
                 "monitor " + std::to_string(monitor) + " does not exist; the monitors are " +
                     platform::describe(monitors) + " (dtlab run --list-monitors lists them)",
                 ErrorKind::environment};
  const platform::Monitor& m = monitors[static_cast<std::size_t>(monitor)];
  std::unique_ptr<ConsoleWindow> c(new ConsoleWindow(participant, participant_imgui));
  platform::WindowOptions wo;
  wo.title = "dtlab - experimenter console";
  wo.width = std::max(640, m.width - 80);
  wo.height = std::max(480, m.height - 120);
  wo.vsync = false;     // the participant's swap is the one synchronised to a display
  wo.focused = false;   // the participant's window keeps the keyboard
  wo.monitor = monitor;
  wo.resizable = false;  // its size is read once (a query per frame is a round trip to the X server)
  auto w = platform::create_window(wo);
  if (!w) {
    participant.make_current();
    return w.error();
  }
  c->window_ = std::move(w.value());
  glfwSetWindowPos(c->window_->glfw(), m.x + 40, m.y + 40);
  glfwGetWindowSize(c->window_->glfw(), &c->size_x_, &c->size_y_);
  c->width_ = c->window_->width();
  c->height_ = c->window_->height();
  c->input_ = std::make_unique<Input>(c->window_->glfw());
  c->text_px_ = std::clamp(static_cast<float>(c->window_->height()) / 28.0f, 20.0f, 48.0f);
  // In the console's GL context, current since create_window.
  auto imgui = detail::create_imgui(c->text_px_, font, c->glyph_ranges_);
  ImGui::SetCurrentContext(participant_imgui);
  if (!imgui) {
    participant.make_current();
    return imgui.error();
  }
  c->imgui_ = imgui.value();
  ImGui::SetCurrentContext(c->imgui_.context);
  ImGui_ImplOpenGL3_CreateDeviceObjects();  // now, in its own GL context: frames that present nothing need none
  ImGui::SetCurrentContext(participant_imgui);
  // The window system asks for the picture again (uncovered, resized): present the next frame whatever it shows.
  g_console = c.get();
  glfwSetWindowRefreshCallback(c->window_->glfw(), [](GLFWwindow*) {
    if (g_console) g_console->refresh_ = true;
  });
  participant.make_current();
  return c;
}

ConsoleWindow::~ConsoleWindow() {
  if (g_console == this) g_console = nullptr;
  if (!window_) return;
  glfwSetWindowRefreshCallback(window_->glfw(), nullptr);
  window_->make_current();
  if (imgui_.context) detail::destroy_imgui(imgui_.context);
  input_.reset();  // its callbacks go before the window
  window_.reset();
  participant_.make_current();
}

bool ConsoleWindow::due(Clock::time_point now, std::chrono::duration<double> budget) const {
  const double age = std::chrono::duration<double>(now - last_frame_).count();
  if (age < 1.0 / kMaxHz) return false;
  return age > kMaxAgeS || budget > last_cost_;
}

void ConsoleWindow::frame(const std::function<void()>& draw, const std::function<void()>& before_swap) {
  const Clock::time_point start = Clock::now();
  const float dt = last_frame_ == Clock::time_point{} ? 1.0f / static_cast<float>(kMaxHz)
                                                      : std::chrono::duration<float>(start - last_frame_).count();
  ImGui::SetCurrentContext(imgui_.context);
  // The console is the experimenter's for the whole session: closing its window changes nothing.
  if (window_->should_close()) glfwSetWindowShouldClose(window_->glfw(), GLFW_FALSE);
  ImGuiIO& io = ImGui::GetIO();
  const int fw = width_, fh = height_;
  io.DisplaySize = ImVec2(static_cast<float>(size_x_), static_cast<float>(size_y_));
  if (size_x_ > 0 && size_y_ > 0)
    io.DisplayFramebufferScale = ImVec2(static_cast<float>(fw) / static_cast<float>(size_x_),
                                        static_cast<float>(fh) / static_cast<float>(size_y_));
  ImGui_ImplOpenGL3_NewFrame();  // its device objects exist since open(): no GL call here
  input_->feed_imgui(dt);
  ImGui::NewFrame();
  draw();
  ImGui::Render();
  input_->new_frame();  // this frame read the edges; events until the next console frame gather anew
  return_keyboard();
  // Rasterising and presenting the window is what costs (software GL: most of a frame); the ImGui
  // frame above does not touch GL. Present only a picture that differs from the one on screen, or
  // when the window system lost it (refresh_).
  if (changed(*ImGui::GetDrawData(), fw, fh) || refresh_) {
    refresh_ = false;
    window_->make_current();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    glClearColor(0.93f, 0.93f, 0.93f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (before_swap) before_swap();
    window_->swap_buffers();
    participant_.make_current();
  }
  ImGui::SetCurrentContext(participant_imgui_);
  last_frame_ = start;
  last_cost_ = Clock::now() - start;
}

bool ConsoleWindow::changed(const ImDrawData& d, int fw, int fh) {
  std::vector<char> now;
  auto put = [&now](const void* p, std::size_t n) { now.insert(now.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n); };
  put(&fw, sizeof fw);
  put(&fh, sizeof fh);
  for (int i = 0; i < d.CmdListsCount; ++i) {
    const ImDrawList& l = *d.CmdLists[i];
    put(l.VtxBuffer.Data, static_cast<std::size_t>(l.VtxBuffer.Size) * sizeof(ImDrawVert));
    put(l.IdxBuffer.Data, static_cast<std::size_t>(l.IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& c : l.CmdBuffer) {
      put(&c.ClipRect, sizeof c.ClipRect);
      put(&c.TextureId, sizeof c.TextureId);
      put(&c.VtxOffset, sizeof c.VtxOffset);
      put(&c.IdxOffset, sizeof c.IdxOffset);
      put(&c.ElemCount, sizeof c.ElemCount);
    }
  }
  if (now == shown_) return false;
  shown_ = std::move(now);
  return true;
}

// The console keeps the keyboard while the pointer is over it or one of its fields is being typed
// in; then (once, so a window manager that refuses is not asked every frame) it goes back to the
// participant's window, whose keys the trial needs.
void ConsoleWindow::return_keyboard() {
  // From the window's events, not queries: a query is a round trip to the X server every frame.
  const bool focused = input_->focused();
  const bool keep = focused && (input_->hovered() || ImGui::IsAnyItemActive());
  if (had_keyboard_ && focused && !keep) {
    glfwFocusWindow(participant_.glfw());
    if (lender_) lender_->lend_pointer(false);
    lender_ = nullptr;
  }
  if (lender_ && !lender_->pointer_lent()) lender_ = nullptr;  // taken back by a click in the participant's window
  had_keyboard_ = keep;
}

void ConsoleWindow::take_keyboard_and_pointer(Input& participant_input) {
  participant_input.lend_pointer(true);
  lender_ = &participant_input;
  glfwFocusWindow(window_->glfw());
  glfwSetCursorPos(window_->glfw(), window_->width() * 0.5, window_->height() * 0.25);
}

}  // namespace dtlab::run
