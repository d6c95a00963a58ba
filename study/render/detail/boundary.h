// Internal: the renderer's public boundary (render.h's error contract). Detail
// code may throw; guarded() runs a public function's body and turns whatever
// it throws into an Error with a kind: PassedError -> its Error; GlFailure (a framebuffer the driver
// calls incomplete, the GL out of memory, a lost context) and std::bad_alloc
// -> environment; std::invalid_argument (a violated precondition found deep
// inside) -> invalid_input; std::logic_error (the frame graph's misuse
// checks) and anything else -> internal. Also classifies a frame's GL errors.
// Never: lets an exception cross render.h.
#pragma once
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/common/error.h"

namespace dtlab::render::detail {

// The GL or the driver failed in a way no caller input explains (environment).
struct GlFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A public function's Error inside another public function (visibility() renders frames):
// thrown by unwrap(), returned unchanged by guarded().
struct PassedError : std::exception {
  explicit PassedError(Error e) : error(std::move(e)) {}
  const char* what() const noexcept override { return error.message.c_str(); }
  Error error;
};
// The value, or throws PassedError with the Error.
template <class T>
T unwrap(Result<T> r) {
  if (!r) throw PassedError(r.error());
  return std::move(r).value();
}

// An Error of `kind` from the renderer's public function `where` ("Renderer::render").
Error render_error(const char* where, const std::string& message, ErrorKind kind);

// The environment Error for a frame whose GL errors (FrameReport::gl_errors, "pass 'x': NAME")
// include GL_OUT_OF_MEMORY or GL_CONTEXT_LOST; nullopt when none does (other GL errors are
// programming errors: they stay in the report, as before).
std::optional<Error> fatal_gl_error(const char* where, const std::vector<std::string>& gl_errors);

// Test builds only (DTLAB_TEST_HOOKS): while the file named by $DTLAB_TEST_RENDER_FAIL_FILE
// exists, every frame reports GL_OUT_OF_MEMORY, so tests can fail a running session's frame on
// cue. The GL error it names, or nullopt (always nullopt without DTLAB_TEST_HOOKS).
std::optional<std::string> injected_gl_error();
// Test builds only (DTLAB_TEST_HOOKS): while $DTLAB_TEST_SHADER_FAIL names `file` (e.g.
// "lens.frag"), programs.cpp ends that shader's source with an #error line, so the driver itself
// refuses it and writes the log. Always false without DTLAB_TEST_HOOKS.
bool injected_shader_failure(std::string_view file);

// Runs `body` (returning Result<T> or Status) and turns an exception into an Error (see above).
template <class R, class F>
R guarded(const char* where, F&& body) noexcept {
  try {
    return body();
  } catch (const PassedError& e) {
    return e.error;
  } catch (const GlFailure& e) {
    return render_error(where, e.what(), ErrorKind::environment);
  } catch (const std::bad_alloc&) {
    return render_error(where, "out of memory (an allocation failed)", ErrorKind::environment);
  } catch (const std::invalid_argument& e) {
    return render_error(where, e.what(), ErrorKind::invalid_input);
  } catch (const std::exception& e) {
    return render_error(where, e.what(), ErrorKind::internal);
  } catch (...) {
    return render_error(where, "an unknown exception", ErrorKind::internal);
  }
}

}  // namespace dtlab::render::detail
