// OpenGL side of the frame graph (see gl_backend.h).
#include <glad/gl.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "study/render/detail/boundary.h"
#include "study/render/detail/gl_backend.h"

namespace dtlab::render::detail {

namespace {
struct Format {
  GLenum internal, format, type;
};
Format gl_format(TextureFormat f) {
  switch (f) {
    case TextureFormat::rgba8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case TextureFormat::rgba16f: return {GL_RGBA16F, GL_RGBA, GL_FLOAT};
    case TextureFormat::rgba32f: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case TextureFormat::r8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case TextureFormat::r16f: return {GL_R16F, GL_RED, GL_FLOAT};
    case TextureFormat::r32f: return {GL_R32F, GL_RED, GL_FLOAT};
    case TextureFormat::r32ui: return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case TextureFormat::depth24_stencil8: return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
    case TextureFormat::depth32f: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
  }
  return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}
}  // namespace

const char* gl_error_name(unsigned code) {
  switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case kGlContextLost: return "GL_CONTEXT_LOST";
    default: return "GL error (unknown code)";
  }
}

GlBackend::~GlBackend() {
  for (auto& [key, fbo] : fbos_) glDeleteFramebuffers(1, &fbo);
  if (!all_textures_.empty()) glDeleteTextures(static_cast<GLsizei>(all_textures_.size()), all_textures_.data());
  if (!all_queries_.empty()) glDeleteQueries(static_cast<GLsizei>(all_queries_.size()), all_queries_.data());
}

unsigned GlBackend::acquire_texture(const TextureDesc& desc) {
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    if (it->desc == desc) {
      const unsigned name = it->name;
      free_.erase(it);
      return name;
    }
  }
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  const Format f = gl_format(desc.format);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(f.internal), desc.width, desc.height, 0, f.format, f.type, nullptr);
  const GLint filter = desc.linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous));
  all_textures_.push_back(name);
  return name;
}

void GlBackend::release_texture(const TextureDesc& desc, unsigned name) { free_.push_back({desc, name, frame_}); }

unsigned GlBackend::acquire_query() {
  if (!free_queries_.empty()) {
    const unsigned q = free_queries_.back();
    free_queries_.pop_back();
    return q;
  }
  GLuint q = 0;
  glGenQueries(1, &q);
  all_queries_.push_back(q);
  return q;
}

void GlBackend::release_query(unsigned name) { free_queries_.push_back(name); }

unsigned GlBackend::framebuffer(const std::vector<unsigned>& color, unsigned depth, TextureFormat depth_format) {
  std::vector<unsigned> key = color;
  key.push_back(depth);
  if (auto it = fbos_.find(key); it != fbos_.end()) return it->second;
  GLint previous_draw = 0, previous_read = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_draw);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
  GLuint fbo = 0;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);  // draw and read: glReadBuffer sets the read framebuffer's
  std::vector<GLenum> buffers;
  for (std::size_t i = 0; i < color.size(); ++i) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D, color[i], 0);
    buffers.push_back(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i));
  }
  if (depth != 0) {
    const GLenum point = depth_format == TextureFormat::depth24_stencil8 ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT;
    glFramebufferTexture2D(GL_FRAMEBUFFER, point, GL_TEXTURE_2D, depth, 0);
  }
  if (buffers.empty()) {
    // Depth only: no colour to draw or read (strict GL 3.3 drivers call it incomplete otherwise).
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
  } else {
    glDrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
  }
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &fbo);
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(status));
    throw GlFailure(std::string("framebuffer incomplete (status ") + hex + "; a texture the driver could not allocate?)");
  }
  fbos_.emplace(std::move(key), fbo);
  return fbo;
}

void GlBackend::begin_condition(unsigned query) { glBeginConditionalRender(query, GL_QUERY_WAIT); }
void GlBackend::end_condition() { glEndConditionalRender(); }

std::optional<bool> GlBackend::query_any(unsigned query, bool wait) {
  if (!wait) {
    GLuint available = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT_AVAILABLE, &available);
    if (available == 0) return std::nullopt;
  }
  GLuint result = 0;
  glGetQueryObjectuiv(query, GL_QUERY_RESULT, &result);
  return result != 0;
}

std::vector<std::string> GlBackend::drain_errors() {
  std::vector<std::string> out;
  for (int i = 0; i < 32; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    out.emplace_back(gl_error_name(e));
  }
  return out;
}

void GlBackend::finish() { glFinish(); }

void GlBackend::delete_texture(unsigned name) {
  for (auto it = fbos_.begin(); it != fbos_.end();) {
    if (std::find(it->first.begin(), it->first.end(), name) != it->first.end()) {
      glDeleteFramebuffers(1, &it->second);
      it = fbos_.erase(it);
    } else {
      ++it;
    }
  }
  glDeleteTextures(1, &name);
  all_textures_.erase(std::remove(all_textures_.begin(), all_textures_.end(), name), all_textures_.end());
}

void GlBackend::end_frame() {
  ++frame_;
  for (auto it = free_.begin(); it != free_.end();) {
    if (frame_ - it->last_used > 8) {
      delete_texture(it->name);
      it = free_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace dtlab::render::detail
