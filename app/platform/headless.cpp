// Headless GL: an OSMesa context with the core profile (3.3 or newer) drawing
// into a buffer this object owns. Guarantees: the context is current after
// create_headless() and after make_current(); the buffer outlives the context.
// Never: falls back to a compatibility profile silently (fails instead).
#include <glad/gl.h>
#include <GL/osmesa.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "app/platform/detail/loader.h"
#include "app/platform/gl_context.h"
#include "app/platform/malloc_tuning.h"

namespace dtlab::platform {

namespace {

class HeadlessContext final : public GlContext {
 public:
  HeadlessContext(OSMesaContext ctx, int w, int h)
      : ctx_(ctx), width_(w), height_(h), buffer_(static_cast<std::size_t>(w) * h * 4) {}
  ~HeadlessContext() override { OSMesaDestroyContext(ctx_); }

  bool bind() {
    detail::switching_to(ContextKind::headless);
    return OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_) != 0;
  }
  void make_current() override {
    bind();
    detail::load_gl_for(ContextKind::headless);
  }
  ContextKind kind() const override { return ContextKind::headless; }
  int width() const override { return width_; }
  int height() const override { return height_; }

 private:
  OSMesaContext ctx_;
  int width_, height_;
  std::vector<unsigned char> buffer_;
};

Error gl_error(std::string message) {
  Error e;
  e.field = "gl";
  e.message = std::move(message);
  return e;
}

}  // namespace

Result<std::unique_ptr<GlContext>> create_headless(int width, int height, int raster_threads) {
  tune_malloc_for_software_gl();
  if (raster_threads >= 0) ::setenv("LP_NUM_THREADS", std::to_string(raster_threads).c_str(), 0);
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return gl_error("headless context size must be 1..16384 pixels per side, got " +
                    std::to_string(width) + "x" + std::to_string(height));
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 24,
                         OSMESA_STENCIL_BITS, 8,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3,
                         OSMESA_CONTEXT_MINOR_VERSION, 3,
                         0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (ctx == nullptr) return gl_error("OSMesa could not create a GL 3.3 core profile context");
  auto context = std::make_unique<HeadlessContext>(ctx, width, height);
  if (!context->bind()) return gl_error("OSMesaMakeCurrent failed");
  const int version = detail::load_gl_for(ContextKind::headless);
  if (version < 33)
    return gl_error("headless GL context offers version " + std::to_string(version / 10) + "." +
                    std::to_string(version % 10) + "; dtlab needs OpenGL 3.3 core");
  detail::pin_gl_threads_of_current_context();
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace dtlab::platform
