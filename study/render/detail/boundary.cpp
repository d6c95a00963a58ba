// The renderer's public boundary (boundary.h): Errors with a kind from what
// detail code throws or the GL reports, and the test builds' fault injection.
// Never: throws.
#include "study/render/detail/boundary.h"

#include <cstdlib>
#include <filesystem>

namespace dtlab::render::detail {

Error render_error(const char* where, const std::string& message, ErrorKind kind) {
  return Error{"", 0, 0, "render", std::string(where) + ": " + message, kind};
}

std::optional<Error> fatal_gl_error(const char* where, const std::vector<std::string>& gl_errors) {
  for (const std::string& e : gl_errors) {
    if (e.find("GL_OUT_OF_MEMORY") != std::string::npos)
      return render_error(where, "the GL ran out of memory (" + e + ")", ErrorKind::environment);
    if (e.find("GL_CONTEXT_LOST") != std::string::npos)
      return render_error(where, "the GL context was lost (" + e + ")", ErrorKind::environment);
  }
  return std::nullopt;
}

std::optional<std::string> injected_gl_error() {
#ifdef DTLAB_TEST_HOOKS
  const char* path = std::getenv("DTLAB_TEST_RENDER_FAIL_FILE");
  std::error_code ec;
  if (path != nullptr && *path != '\0' && std::filesystem::exists(path, ec))
    return std::string("GL_OUT_OF_MEMORY (injected: $DTLAB_TEST_RENDER_FAIL_FILE exists)");
#endif
  return std::nullopt;
}

bool injected_shader_failure(std::string_view file) {
#ifdef DTLAB_TEST_HOOKS
  const char* name = std::getenv("DTLAB_TEST_SHADER_FAIL");
  return name != nullptr && file == name;
#else
  (void)file;
  return false;
#endif
}

}  // namespace dtlab::render::detail
