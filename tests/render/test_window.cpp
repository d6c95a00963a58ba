// The same renderer in a GLFW window (run under xvfb-run) and in the OSMesa
// headless context: every method gives the same pixels in both, and drawing
// into the window's default framebuffer leaves the GL state the caller had
// (a UI drawn afterwards relies on it). Also switches between the two
// contexts in one process, which reloads glad's function pointers.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <memory>

#include "app/platform/gl_context.h"
#include "tests/render/scenes.h"

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
  for (Method m : {Method::standard, Method::dt_seed, Method::dt_fast, Method::reference}) {
    SCOPED_TRACE(std::string(to_string(m)));
    FrameSettings settings;
    settings.method = m;
    settings.timed = true;
    // Window: render into the default framebuffer (an imported target).
    win.make_current();
    Image in_window;
    {
      auto r = Renderer::create(s);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      const FrameReport rep = (*r)->render(cam, settings, ImportedTarget{0, kW, kH});
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      in_window = (*r)->read_color();
    }
    win.swap_buffers();
    // Headless.
    platform::GlContext& headless = testing::headless_context();
    Image offscreen;
    {
      auto r = Renderer::create(s);
      ASSERT_TRUE(r.ok()) << r.error().to_string();
      const FrameReport rep = (*r)->render_offscreen(cam, settings, kW, kH);
      EXPECT_TRUE(rep.gl_errors.empty()) << rep.gl_errors.front();
      offscreen = (*r)->read_color();
    }
    (void)headless;
    const ImageDiff d = compare(in_window, offscreen);
    EXPECT_LE(d.max_abs, 1) << "mae " << d.mae;
    // Not a blank frame: the target region differs from the wall in the effect methods.
    int distinct = 0;
    for (std::size_t i = 0; i + 4 < offscreen.rgba.size(); i += 4) distinct += offscreen.rgba[i] != offscreen.rgba[i + 4];
    EXPECT_GT(distinct, 100);
    testing::maybe_dump(in_window, "-" + std::string(to_string(m)));
  }
}

TEST(Window, RenderingIntoTheWindowRestoresTheCallersGlState) {
  auto window = platform::create_window({"dtlab test", kW, kH, true, false, false});
  ASSERT_TRUE(window.ok()) << window.error().to_string();
  (*window)->make_current();
  auto r = Renderer::create(scene_with_target_behind_wall());
  ASSERT_TRUE(r.ok());
  // A caller's state, as a UI might leave it.
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glEnable(GL_SCISSOR_TEST);
  glScissor(3, 4, 50, 60);
  glViewport(1, 2, 100, 90);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
  glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  glActiveTexture(GL_TEXTURE2);
  for (Method m : {Method::standard, Method::dt_seed, Method::dt_fast, Method::reference}) {
    FrameSettings settings;
    settings.method = m;
    (*r)->render(testing::front_camera(kW, kH), settings, ImportedTarget{0, kW, kH});
    GLint v[4] = {};
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, v);
    EXPECT_EQ(v[0], static_cast<GLint>(vao));
    glGetIntegerv(GL_SCISSOR_BOX, v);
    EXPECT_EQ(v[0], 3);
    EXPECT_EQ(v[3], 60);
    glGetIntegerv(GL_VIEWPORT, v);
    EXPECT_EQ(v[0], 1);
    EXPECT_EQ(v[2], 100);
    EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
    EXPECT_TRUE(glIsEnabled(GL_BLEND));
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
    EXPECT_FALSE(glIsEnabled(GL_STENCIL_TEST));
    glGetIntegerv(GL_BLEND_SRC_RGB, v);
    EXPECT_EQ(v[0], GL_SRC_ALPHA);
    glGetIntegerv(GL_BLEND_DST_ALPHA, v);
    EXPECT_EQ(v[0], GL_ZERO);
    GLboolean cm[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, cm);
    EXPECT_FALSE(cm[1]);
    glGetIntegerv(GL_ACTIVE_TEXTURE, v);
    EXPECT_EQ(v[0], GL_TEXTURE2);
    GLfloat cc[4];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    EXPECT_FLOAT_EQ(cc[2], 0.75f);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, v);
    EXPECT_EQ(v[0], 0);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  }
  r.value().reset();
  glDeleteVertexArrays(1, &vao);
}

}  // namespace
}  // namespace dtlab::render
