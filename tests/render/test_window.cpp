// The same renderer in a GLFW window (run under xvfb-run) and in the OSMesa
// headless context: every method gives the same pixels in both, and drawing
// into the window's default framebuffer leaves the GL state the caller had
// (a UI drawn afterwards relies on it). Also switches between the two
// contexts in one process, which reloads glad's function pointers.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "app/platform/gl_context.h"
#include "tests/render/scenes.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

constexpr int kW = 256, kH = 192;

scene::Scene scene_with_target_behind_wall() {
  scene::Scene s;
  testing::add_object(s, testing::quad_mesh(-40, -40, 40, 40, -20), {0.3f, 0.7f, 0.3f});
  testing::add_object(s, testing::sphere_mesh({0, 0, -12}, 2.0f), {1, 0, 0}, true);
  testing::add_object(s, testing::quad_mesh(-5, -4, 5, 4, -8), {0.2f, 0.3f, 0.9f});
  testing::add_object(s, testing::box_mesh({2, 1, -10}, {4, 3, -9}), {0.9f, 0.8f, 0.1f});
  return s;
}

TEST(Window, EveryMethodGivesTheSamePixelsInAWindowAndHeadless) {
  auto window = platform::create_window({"dtlab test", kW, kH, true, false, false});
  ASSERT_TRUE(window.ok()) << window.error().to_string();
  platform::Window& win = **window;
  ASSERT_EQ(win.width(), kW);
  ASSERT_EQ(win.height(), kH);
  const scene::Scene s = scene_with_target_behind_wall();
  const Camera cam = testing::front_camera(kW, kH);
  for (Method m : {Method::standard, Method::dt_seed, Method::dt_fast, Method::reference, Method::lens,
                   Method::screen_door, Method::vdt}) {
    SCOPED_TRACE(std::string(to_string(m)));
    FrameSettings settings;
    settings.method = m;
    settings.lens.center = {kW / 2.0f, kH / 2.0f};
    settings.timed = true;
    // Window: render into the default framebuffer (an imported target).
    win.make_current();
    Image in_window;
    {
      auto r = Renderer::create(s);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      const FrameReport rep = must((*r)->render(cam, settings, ImportedTarget{0, kW, kH}));
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      in_window = must((*r)->read_color());
    }
    win.swap_buffers();
    // Headless.
    platform::GlContext& headless = testing::headless_context();
    Image offscreen;
    {
      auto r = Renderer::create(s);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      const FrameReport rep = must((*r)->render_offscreen(cam, settings, kW, kH));
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      offscreen = must((*r)->read_color());
    }
    (void)headless;
    const ImageDiff d = must(compare(in_window, offscreen));
    EXPECT_LE(d.max_abs, 1) << "mae " << d.mae;
    // Not a blank frame: the target region differs from the wall in the effect methods.
    int distinct = 0;
    for (std::size_t i = 0; i + 4 < offscreen.rgba.size(); i += 4) distinct += offscreen.rgba[i] != offscreen.rgba[i + 4];
    EXPECT_GT(distinct, 100);
    testing::maybe_dump(in_window, "-" + std::string(to_string(m)));
  }
}

// A caller's state, as a UI (or careless code) might leave it: every piece of state the
// renderer saves, restores or sets a baseline for, at a value that is not GL's default.
struct CallerState {
  GLuint vao = 0, array_buffer = 0, pack_buffer = 0, unpack_buffer = 0, sampler = 0;
  GLuint textures[4] = {};

  void set() {
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &array_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, array_buffer);
    glGenBuffers(1, &pack_buffer);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
    glBufferData(GL_PIXEL_PACK_BUFFER, 64, nullptr, GL_STREAM_READ);
    glGenBuffers(1, &unpack_buffer);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack_buffer);
    glBufferData(GL_PIXEL_UNPACK_BUFFER, 64, nullptr, GL_STREAM_DRAW);
    glGenTextures(4, textures);
    for (int i = 0; i < 4; ++i) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
      glBindTexture(GL_TEXTURE_2D, textures[i]);
    }
    glGenSamplers(1, &sampler);  // nearest filtering would spoil the renderer's bilinear masks
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindSampler(0, sampler);
    glActiveTexture(GL_TEXTURE2);
    glReadBuffer(GL_FRONT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(3, 4, 50, 60);
    glViewport(1, 2, 100, 90);
    glDepthRange(0.2, 0.8);
    for (GLenum cap : kEnabled) glEnable(cap);
    glDisable(GL_DITHER);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glFrontFace(GL_CW);
    glCullFace(GL_FRONT);
    glLogicOp(GL_XOR);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glBlendEquationSeparate(GL_MIN, GL_MAX);
    glBlendColor(0.1f, 0.2f, 0.3f, 0.4f);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glStencilFuncSeparate(GL_FRONT, GL_LESS, 3, 0x0F);
    glStencilFuncSeparate(GL_BACK, GL_GREATER, 5, 0xF0);
    glStencilOpSeparate(GL_FRONT, GL_INCR, GL_DECR, GL_INVERT);
    glStencilOpSeparate(GL_BACK, GL_ZERO, GL_REPLACE, GL_INCR_WRAP);
    glStencilMaskSeparate(GL_FRONT, 0x3C);
    glStencilMaskSeparate(GL_BACK, 0xC3);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_PACK_ROW_LENGTH, 7);
    glPixelStorei(GL_PACK_SKIP_ROWS, 1);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 5);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 3);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 4);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClearDepth(0.5);
    glClearStencil(9);
  }

  // Every value set() left, read back; `after` names the call the state must have survived.
  void expect_unchanged(const std::string& after) const {
    SCOPED_TRACE(after);
    auto i = [](GLenum e, int k = 0) {
      GLint v[4] = {};
      glGetIntegerv(e, v);
      return v[k];
    };
    EXPECT_EQ(i(GL_VERTEX_ARRAY_BINDING), static_cast<GLint>(vao));
    EXPECT_EQ(i(GL_ARRAY_BUFFER_BINDING), static_cast<GLint>(array_buffer));
    EXPECT_EQ(i(GL_PIXEL_PACK_BUFFER_BINDING), static_cast<GLint>(pack_buffer));
    EXPECT_EQ(i(GL_PIXEL_UNPACK_BUFFER_BINDING), static_cast<GLint>(unpack_buffer));
    EXPECT_EQ(i(GL_ACTIVE_TEXTURE), GL_TEXTURE2);
    for (int u = 0; u < 4; ++u) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
      EXPECT_EQ(i(GL_TEXTURE_BINDING_2D), static_cast<GLint>(textures[u])) << "unit " << u;
      EXPECT_EQ(i(GL_SAMPLER_BINDING), u == 0 ? static_cast<GLint>(sampler) : 0) << "unit " << u;
    }
    glActiveTexture(GL_TEXTURE2);
    EXPECT_EQ(i(GL_DRAW_FRAMEBUFFER_BINDING), 0);
    EXPECT_EQ(i(GL_READ_FRAMEBUFFER_BINDING), 0);
    EXPECT_EQ(i(GL_READ_BUFFER), GL_FRONT);
    EXPECT_EQ(i(GL_SCISSOR_BOX, 0), 3);
    EXPECT_EQ(i(GL_SCISSOR_BOX, 3), 60);
    EXPECT_EQ(i(GL_VIEWPORT, 0), 1);
    EXPECT_EQ(i(GL_VIEWPORT, 2), 100);
    GLdouble range[2] = {};
    glGetDoublev(GL_DEPTH_RANGE, range);
    EXPECT_FLOAT_EQ(static_cast<float>(range[0]), 0.2f);  // stored as float
    EXPECT_FLOAT_EQ(static_cast<float>(range[1]), 0.8f);
    EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
    for (GLenum cap : kEnabled) EXPECT_TRUE(glIsEnabled(cap)) << "capability 0x" << std::hex << cap;
    EXPECT_FALSE(glIsEnabled(GL_DITHER));
    EXPECT_EQ(i(GL_POLYGON_MODE), GL_LINE);
    EXPECT_EQ(i(GL_FRONT_FACE), GL_CW);
    EXPECT_EQ(i(GL_CULL_FACE_MODE), GL_FRONT);
    EXPECT_EQ(i(GL_LOGIC_OP_MODE), GL_XOR);
    EXPECT_EQ(i(GL_BLEND_SRC_RGB), GL_SRC_ALPHA);
    EXPECT_EQ(i(GL_BLEND_DST_ALPHA), GL_ZERO);
    EXPECT_EQ(i(GL_BLEND_EQUATION_RGB), GL_MIN);
    EXPECT_EQ(i(GL_BLEND_EQUATION_ALPHA), GL_MAX);
    GLfloat bc[4] = {};
    glGetFloatv(GL_BLEND_COLOR, bc);
    EXPECT_FLOAT_EQ(bc[3], 0.4f);
    EXPECT_FLOAT_EQ(bc[0], 0.1f);
    EXPECT_EQ(i(GL_DEPTH_FUNC), GL_GEQUAL);
    GLboolean b = GL_TRUE;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
    EXPECT_FALSE(b);
    EXPECT_EQ(i(GL_STENCIL_FUNC), GL_LESS);
    EXPECT_EQ(i(GL_STENCIL_BACK_REF), 5);
    EXPECT_EQ(i(GL_STENCIL_VALUE_MASK), 0x0F);
    EXPECT_EQ(i(GL_STENCIL_PASS_DEPTH_PASS), GL_INVERT);
    EXPECT_EQ(i(GL_STENCIL_BACK_PASS_DEPTH_PASS), GL_INCR_WRAP);
    EXPECT_EQ(i(GL_STENCIL_WRITEMASK), 0x3C);
    EXPECT_EQ(i(GL_STENCIL_BACK_WRITEMASK), 0xC3);
    GLboolean cm[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, cm);
    EXPECT_TRUE(cm[0] && !cm[1] && cm[2] && !cm[3]);
    EXPECT_EQ(i(GL_PACK_ALIGNMENT), 2);
    EXPECT_EQ(i(GL_PACK_ROW_LENGTH), 7);
    EXPECT_EQ(i(GL_PACK_SKIP_ROWS), 1);
    EXPECT_EQ(i(GL_PACK_SKIP_PIXELS), 2);
    EXPECT_EQ(i(GL_UNPACK_ALIGNMENT), 8);
    EXPECT_EQ(i(GL_UNPACK_ROW_LENGTH), 5);
    EXPECT_EQ(i(GL_UNPACK_SKIP_ROWS), 3);
    EXPECT_EQ(i(GL_UNPACK_SKIP_PIXELS), 4);
    GLfloat cc[4];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    EXPECT_FLOAT_EQ(cc[2], 0.75f);
    GLdouble cd = 0;
    glGetDoublev(GL_DEPTH_CLEAR_VALUE, &cd);
    EXPECT_DOUBLE_EQ(cd, 0.5);
    EXPECT_EQ(i(GL_STENCIL_CLEAR_VALUE), 9);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  }

  void release() {
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    const GLuint buffers[3] = {array_buffer, pack_buffer, unpack_buffer};
    glDeleteBuffers(3, buffers);
    glDeleteTextures(4, textures);
    glDeleteSamplers(1, &sampler);
  }

  static constexpr GLenum kEnabled[] = {
      GL_BLEND,         GL_DEPTH_TEST,        GL_CULL_FACE,       GL_STENCIL_TEST, GL_POLYGON_OFFSET_FILL,
      GL_SAMPLE_ALPHA_TO_COVERAGE, GL_COLOR_LOGIC_OP, GL_RASTERIZER_DISCARD, GL_DEPTH_CLAMP,
      GL_FRAMEBUFFER_SRGB, GL_PRIMITIVE_RESTART, GL_CLIP_DISTANCE0, GL_SAMPLE_MASK};
};

// Drawing into the window's default framebuffer leaves every piece of the caller's state as
// it was, and the caller's state cannot change the frame: each method gives the same pixels
// under the hostile state as under GL's defaults.
TEST(Window, RenderingIntoTheWindowRestoresTheCallersGlStateAndIgnoresIt) {
  auto window = platform::create_window({"dtlab test", kW, kH, true, false, false});
  ASSERT_TRUE(window.ok()) << window.error().to_string();
  (*window)->make_current();
  auto r = Renderer::create(scene_with_target_behind_wall());
  ASSERT_TRUE(r.ok());
  const Camera cam = testing::front_camera(kW, kH);
  const std::vector<Method> methods{Method::standard, Method::dt_seed, Method::dt_fast,
                                    Method::reference, Method::lens, Method::screen_door, Method::vdt};
  std::vector<Image> clean;
  for (Method m : methods) {
    FrameSettings settings;
    settings.method = m;
    settings.lens.center = {kW / 2.0f, kH / 2.0f};
    must((*r)->render(cam, settings, ImportedTarget{0, kW, kH}));
    clean.push_back(must((*r)->read_color()));
  }
  CallerState caller;
  caller.set();
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (std::size_t k = 0; k < methods.size(); ++k) {
    SCOPED_TRACE(std::string(to_string(methods[k])));
    FrameSettings settings;
    settings.method = methods[k];
    settings.lens.center = {kW / 2.0f, kH / 2.0f};
    const FrameReport rep = must((*r)->render(cam, settings, ImportedTarget{0, kW, kH}));
    EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
    caller.expect_unchanged("render");
    const Image img = must((*r)->read_color());
    caller.expect_unchanged("read_color");
    EXPECT_LE(must(compare(img, clean[k])).max_abs, 1) << "the caller's state changed the frame";
  }
  r.value().reset();
  caller.release();
}

}  // namespace
}  // namespace dtlab::render
