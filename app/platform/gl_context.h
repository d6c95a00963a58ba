// OpenGL contexts for dtlab: a headless OSMesa context (tests, `dtlab render`,
// `dtlab bench`, simulated sessions) and a GLFW window (participant sessions).
// Guarantees: a context returned here is OpenGL 3.3 core or newer, is current
// on the calling thread, and has the GL functions loaded through glad for its
// kind; make_current() reloads them when switching between kinds.
// Never: draws anything, or hides a context failure (it is an Error value).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "study/common/error.h"

struct GLFWwindow;

namespace dtlab::platform {

enum class ContextKind { headless, window };

// A GL 3.3 core context. Its default framebuffer (name 0) has width() x height() pixels.
class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  virtual void make_current() = 0;     // makes this context current on this thread; GL calls then go to it
  virtual ContextKind kind() const = 0;
  virtual int width() const = 0;       // default framebuffer width in pixels
  virtual int height() const = 0;      // default framebuffer height in pixels
  std::string description() const;    // "GL_VERSION / GL_RENDERER" of this context (makes it current)

 protected:
  GlContext() = default;
};

// Creates an OSMesa context (core profile 3.3) whose default framebuffer is
// width x height RGBA8 with depth and stencil; current on return. `raster_threads` >= 0 asks the
// software rasterizer (llvmpipe's LP_NUM_THREADS) for that many threads, 0 = rasterize in the
// calling thread; it takes effect only for the process's first context and never overrides
// LP_NUM_THREADS set in the environment. -1: the driver's default (one thread per core).
Result<std::unique_ptr<GlContext>> create_headless(int width, int height, int raster_threads = -1);

struct WindowOptions {
  std::string title = "dtlab";
  int width = 1024;
  int height = 768;
  bool visible = true;   // false: an off-screen window (tests under xvfb)
  bool vsync = true;
  bool resizable = true;
  bool fullscreen = false;  // full screen on `monitor`, at that monitor's current video mode (width/height ignored)
  int monitor = 0;          // 0-based index into monitors() (0 = the primary one)
  bool focused = true;      // false: opens without taking the keyboard focus from the window that has it
};

// A connected monitor: GLFW's name, its place on the desktop and its current video mode.
struct Monitor {
  std::string name;
  int x = 0, y = 0, width = 0, height = 0;  // desktop coordinates (screen points)
  int refresh_hz = 0;                       // 0: the monitor does not say
};

// The connected monitors, primary first, in the order --monitor N numbers them (initialises GLFW
// for the call when no window is open); empty when there is no display.
std::vector<Monitor> monitors();
// One line per monitor for messages and --list-monitors: "0: DUMMY0, 1280x1024 at 0,0, 60 Hz".
std::string describe(const std::vector<Monitor>& monitors);

// A GLFW window with a GL 3.3 core context (forward compatible, so macOS works).
class Window final : public GlContext {
 public:
  ~Window() override;
  void make_current() override;
  ContextKind kind() const override { return ContextKind::window; }
  int width() const override;          // framebuffer pixels (not screen points)
  int height() const override;
  GLFWwindow* glfw() const { return window_; }  // for input and UI backends; valid until destruction
  bool should_close() const;
  void swap_buffers();
  void poll_events();

 private:
  friend Result<std::unique_ptr<Window>> create_window(const WindowOptions&);
  explicit Window(GLFWwindow* w) : window_(w) {}
  GLFWwindow* window_ = nullptr;
};

// Opens a window; fails with an Error (no display, no GL 3.3) instead of aborting.
Result<std::unique_ptr<Window>> create_window(const WindowOptions& options);

}  // namespace dtlab::platform
