// The OpenGL implementation of FrameGraphBackend: a pool of textures keyed
// by description, a cache of framebuffers keyed by attachments, a pool of
// occlusion queries, conditional rendering and glGetError draining.
// Guarantees: every GL object it creates it deletes (destructor, or end_frame()
// for pooled textures unused for a few frames); a framebuffer the driver
// calls incomplete throws GlFailure (boundary.h: an environment Error at
// render.h). Needs a current GL context.
// Never: changes GL state other than object creation and the framebuffer
// binding it restores in framebuffer().
#pragma once
#include <map>
#include <vector>

#include "study/render/detail/frame_graph.h"

namespace dtlab::render::detail {

class GlBackend final : public FrameGraphBackend {
 public:
  GlBackend() = default;
  ~GlBackend() override;
  GlBackend(const GlBackend&) = delete;
  GlBackend& operator=(const GlBackend&) = delete;

  unsigned acquire_texture(const TextureDesc& desc) override;
  void release_texture(const TextureDesc& desc, unsigned name) override;
  unsigned acquire_query() override;
  void release_query(unsigned name) override;
  unsigned framebuffer(const std::vector<unsigned>& color, unsigned depth, TextureFormat depth_format) override;
  void begin_condition(unsigned query) override;
  void end_condition() override;
  std::optional<bool> query_any(unsigned query, bool wait) override;
  std::vector<std::string> drain_errors() override;
  void finish() override;

  void end_frame();  // ages the pool; deletes textures (and their framebuffers) unused for 8 frames

 private:
  struct Pooled {
    TextureDesc desc;
    unsigned name;
    long last_used;
  };
  void delete_texture(unsigned name);
  std::vector<Pooled> free_;              // textures ready for reuse
  std::vector<unsigned> all_textures_;    // every texture created and not deleted
  std::map<std::vector<unsigned>, unsigned> fbos_;  // key: colour names..., depth name
  std::vector<unsigned> free_queries_, all_queries_;
  long frame_ = 0;
};

// GL_CONTEXT_LOST (GL 4.5, KHR_robustness): glGetError's code after a reset; the 3.3 loader lacks the name.
inline constexpr unsigned kGlContextLost = 0x0507;
const char* gl_error_name(unsigned code);  // "GL_INVALID_ENUM", ..., "GL_CONTEXT_LOST"

}  // namespace dtlab::render::detail
