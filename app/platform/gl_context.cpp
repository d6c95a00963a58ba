// Shared part of the platform layer: the glad loader switch and the context
// description. The loader pointers are process-global (glad's design); this
// file is the only writer of them.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/osmesa.h>

#include <optional>
#include <string>

#include "app/platform/detail/loader.h"
#include "app/platform/gl_context.h"
#include "app/platform/thread_pinning.h"

namespace dtlab::platform {

namespace detail {

namespace {
std::optional<ContextKind> g_loaded_kind;  // kind whose entry points glad holds
int g_loaded_version = 0;

GLADapiproc osmesa_proc(const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
}
std::optional<ContextKind> g_current_kind;  // kind of the context made current last
}  // namespace

void switching_to(ContextKind kind) {
  if (g_current_kind && *g_current_kind != kind) {
    if (*g_current_kind == ContextKind::window) {
      glfwMakeContextCurrent(nullptr);
    } else {
      OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    }
  }
  g_current_kind = kind;
}

void window_released() {
  if (g_current_kind == ContextKind::window) g_current_kind.reset();
}

int load_gl_for(ContextKind kind) {
  if (g_loaded_kind == kind && g_loaded_version != 0) return g_loaded_version;
  const int v = kind == ContextKind::headless
                    ? gladLoadGL(osmesa_proc)
                    : gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress));
  g_loaded_kind = v != 0 ? std::optional<ContextKind>(kind) : std::nullopt;
  g_loaded_version = v == 0 ? 0 : GLAD_VERSION_MAJOR(v) * 10 + GLAD_VERSION_MINOR(v);
  return g_loaded_version;
}

int pin_gl_threads_of_current_context() {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glFinish();
  return pin_software_gl_threads();
}

}  // namespace detail

std::string GlContext::description() const {
  const_cast<GlContext*>(this)->make_current();
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s != nullptr ? s : "?");
  };
  return str(GL_VERSION) + " / " + str(GL_RENDERER);
}

}  // namespace dtlab::platform
