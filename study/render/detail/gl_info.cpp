// current_gl_description (gl_info.h).
#include <glad/gl.h>

#include "study/render/gl_info.h"

namespace dtlab::render {

std::string current_gl_description() {
  if (glad_glGetString == nullptr) return "no GL loaded";  // e.g. a responder that draws nothing
  auto str = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return str(GL_VERSION) + " / " + str(GL_RENDERER);
}

}  // namespace dtlab::render
