// Windowed GL: a GLFW window with an OpenGL 3.3 core, forward-compatible
// context. GLFW is initialised on the first window and terminated after the
// last one closes. Guarantees: failures (no display, no GL 3.3) come back as
// Error values with GLFW's own description. Never: calls exit() or abort().
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <memory>
#include <string>

#include "app/platform/detail/loader.h"
#include "app/platform/gl_context.h"
#include "app/platform/malloc_tuning.h"

namespace dtlab::platform {

namespace {

int g_windows = 0;           // open windows; GLFW is initialised while > 0
std::string g_last_error;    // GLFW's last error description

void on_glfw_error(int code, const char* description) {
  g_last_error = "GLFW error " + std::to_string(code) + ": " + (description ? description : "?");
}

Error window_error(std::string message) {
  Error e;
  e.field = "window";
  e.message = std::move(message);
  if (!g_last_error.empty()) e.message += " (" + g_last_error + ")";
  return e;
}

}  // namespace

Window::~Window() {
  if (glfwGetCurrentContext() == window_) detail::window_released();
  glfwDestroyWindow(window_);
  if (--g_windows == 0) glfwTerminate();
}

void Window::make_current() {
  detail::switching_to(ContextKind::window);
  glfwMakeContextCurrent(window_);
  detail::load_gl_for(ContextKind::window);
}

int Window::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w;
}

int Window::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return h;
}

bool Window::should_close() const { return glfwWindowShouldClose(window_) != 0; }
void Window::swap_buffers() { glfwSwapBuffers(window_); }
void Window::poll_events() { glfwPollEvents(); }

Result<std::unique_ptr<Window>> create_window(const WindowOptions& options) {
  tune_malloc_for_software_gl();
  if (options.width <= 0 || options.height <= 0)
    return window_error("window size must be positive, got " + std::to_string(options.width) + "x" +
                        std::to_string(options.height));
  glfwSetErrorCallback(on_glfw_error);
  g_last_error.clear();
  if (g_windows == 0 && glfwInit() == GLFW_FALSE) return window_error("cannot initialise GLFW (is there a display?)");
  ++g_windows;  // from here on the Window destructor (or the failure path) balances it
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, options.resizable ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_ALPHA_BITS, 8);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  glfwWindowHint(GLFW_FOCUSED, options.focused ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_FOCUS_ON_SHOW, options.focused ? GLFW_TRUE : GLFW_FALSE);
  // A full-screen participant window stays up when the keyboard goes elsewhere (the experimenter
  // console's window on another monitor); GLFW's default would iconify it.
  glfwWindowHint(GLFW_AUTO_ICONIFY, GLFW_FALSE);
  GLFWmonitor* monitor = nullptr;
  int width = options.width, height = options.height;
  int place_x = -1, place_y = -1;  // a windowed window on another monitor: its top-left corner
  if (options.fullscreen || options.monitor != 0) {
    int count = 0;
    GLFWmonitor** connected = glfwGetMonitors(&count);
    if (options.monitor < 0 || options.monitor >= count) {
      Error e = window_error("monitor " + std::to_string(options.monitor) + " does not exist (" +
                             std::to_string(count) + " connected, numbered from 0: " + describe(monitors()) + ")");
      if (--g_windows == 0) glfwTerminate();
      return e;
    }
    if (options.fullscreen) {
      monitor = connected[options.monitor];
      const GLFWvidmode* mode = glfwGetVideoMode(monitor);
      width = mode->width;
      height = mode->height;
      glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
    } else {
      glfwGetMonitorPos(connected[options.monitor], &place_x, &place_y);
    }
  }
  GLFWwindow* w = glfwCreateWindow(width, height, options.title.c_str(), monitor, nullptr);
  if (w == nullptr) {
    if (--g_windows == 0) glfwTerminate();
    return window_error("cannot open a window with an OpenGL 3.3 core context");
  }
  if (place_x >= 0) glfwSetWindowPos(w, place_x + 40, place_y + 40);
  std::unique_ptr<Window> window(new Window(w));
  detail::switching_to(ContextKind::window);
  glfwMakeContextCurrent(w);
  const int version = detail::load_gl_for(ContextKind::window);
  if (version < 33) return window_error("the window's GL context is older than 3.3 core");
  glfwSwapInterval(options.vsync ? 1 : 0);
  detail::pin_gl_threads_of_current_context();
  return window;
}

std::vector<Monitor> monitors() {
  std::vector<Monitor> out;
  const bool init = g_windows == 0;
  if (init && glfwInit() == GLFW_FALSE) return out;
  int count = 0;
  GLFWmonitor** list = glfwGetMonitors(&count);
  for (int i = 0; i < count; ++i) {
    Monitor m;
    const char* name = glfwGetMonitorName(list[i]);
    m.name = name ? name : "monitor " + std::to_string(i);
    glfwGetMonitorPos(list[i], &m.x, &m.y);
    if (const GLFWvidmode* mode = glfwGetVideoMode(list[i])) {
      m.width = mode->width;
      m.height = mode->height;
      m.refresh_hz = mode->refreshRate;
    }
    out.push_back(std::move(m));
  }
  if (init) glfwTerminate();
  return out;
}

std::string describe(const std::vector<Monitor>& monitors) {
  if (monitors.empty()) return "no monitor";
  std::string s;
  for (std::size_t i = 0; i < monitors.size(); ++i) {
    const Monitor& m = monitors[i];
    if (i) s += "; ";
    s += std::to_string(i) + ": " + m.name + ", " + std::to_string(m.width) + "x" + std::to_string(m.height) + " at " +
         std::to_string(m.x) + "," + std::to_string(m.y);
    if (m.refresh_hz > 0) s += ", " + std::to_string(m.refresh_hz) + " Hz";
  }
  return s;
}

}  // namespace dtlab::platform
