// The renderer's error contract (render.h, docs/render.md "Errors"): no
// public function throws; a frame the GL cannot allocate (a target wider
// than GL_MAX_TEXTURE_SIZE: the driver leaves the texture without storage
// and calls its framebuffer incomplete) is an Error of kind environment, and
// the same renderer draws the next frame exactly as a fresh one does; bad
// sizes and settings are invalid_input Errors naming what was wrong; the test
// builds' injected GL_OUT_OF_MEMORY ($DTLAB_TEST_RENDER_FAIL_FILE) fails
// frames only while its file exists.
#include <glad/gl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/must.h"
#include "tests/render/scenes.h"

using dtlab::test::must;

namespace dtlab::render {
namespace {

using testing::add_object;
using testing::box_mesh;
using testing::front_camera;
using testing::quad_mesh;

constexpr int kW = 96, kH = 72;

// A target behind an occluder: dt-fast runs its effect passes (masks, atlas, composite).
scene::Scene occluded_target() {
  scene::Scene s;
  add_object(s, quad_mesh(-30, -30, 30, 30, -25), {0.2f, 0.8f, 0.3f});
  add_object(s, box_mesh({-1, -1, -14}, {1, 1, -12}), {1, 0, 0}, true);
  add_object(s, quad_mesh(-3, -3, 3, 3, -8), {0.1f, 0.3f, 0.9f});
  return s;
}

FrameSettings dt_fast() {
  FrameSettings f;
  f.method = Method::dt_fast;
  return f;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Each method's first frame over a target the GL cannot allocate: an environment Error naming
// the incomplete framebuffer, never an exception. Then a normal frame from the same renderer is
// byte-identical to a fresh renderer's (no GL state, conditional render or pooled texture of the
// failed frame leaks into it).
TEST(RenderErrors, AFrameTheGlCannotAllocateIsAnEnvironmentErrorAndTheNextFrameIsExact) {
  testing::headless_context();
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  ASSERT_GT(max_side, 0);
  for (Method m : {Method::standard, Method::dt_fast, Method::dt_seed, Method::vdt}) {
    SCOPED_TRACE(std::string(to_string(m)));
    auto r = Renderer::create(occluded_target());
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    FrameSettings f = dt_fast();
    f.method = m;
    const auto failed = (*r)->render(front_camera(max_side + 1, 1), f, ImportedTarget{0, max_side + 1, 1});
    ASSERT_FALSE(failed.ok()) << "a " << max_side + 1 << " x 1 frame beyond GL_MAX_TEXTURE_SIZE rendered";
    EXPECT_EQ(failed.error().kind, ErrorKind::environment) << failed.error().to_string();
    EXPECT_EQ(failed.error().field, "render");
    EXPECT_TRUE(contains(failed.error().message, "Renderer::render: framebuffer incomplete"))
        << failed.error().message;

    must((*r)->render_offscreen(front_camera(kW, kH), f, kW, kH));
    const Image after = must((*r)->read_color());
    auto fresh = Renderer::create(occluded_target());
    ASSERT_TRUE(fresh.ok());
    must((*fresh)->render_offscreen(front_camera(kW, kH), f, kW, kH));
    const Image expected = must((*fresh)->read_color());
    EXPECT_EQ(after.rgba, expected.rgba) << "the frame after the failure differs from a fresh renderer's";
  }
}

// Sizes outside the documented ranges and settings check() refuses: invalid_input Errors that say
// which function and what was expected; nothing is drawn.
TEST(RenderErrors, BadSizesAndSettingsAreInvalidInputErrors) {
  testing::headless_context();
  auto r = Renderer::create(occluded_target());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  Renderer& renderer = *r.value();
  const Camera cam = front_camera(kW, kH);
  auto expect_invalid = [](const Error& e, const std::string& where, const std::string& what) {
    EXPECT_EQ(e.kind, ErrorKind::invalid_input) << e.to_string();
    EXPECT_TRUE(contains(e.message, where)) << e.message;
    EXPECT_TRUE(contains(e.message, what)) << e.message;
  };
  const auto zero = renderer.render(cam, dt_fast(), ImportedTarget{0, 0, kH});
  ASSERT_FALSE(zero.ok());
  expect_invalid(zero.error(), "Renderer::render", "target size must be positive, got 0x72");
  const auto huge = renderer.render_offscreen(cam, dt_fast(), 16385, kH);
  ASSERT_FALSE(huge.ok());
  expect_invalid(huge.error(), "Renderer::render_offscreen", "size must be 1..16384, got 16385x72");
  const auto region = renderer.effect_region(cam, DtSettings{}, kW, 0);
  ASSERT_FALSE(region.ok());
  expect_invalid(region.error(), "Renderer::effect_region", "size must be 1..16384");

  FrameSettings bad = dt_fast();
  bad.dt.alpha_start = 1.5f;
  const auto frame = renderer.render_offscreen(cam, bad, kW, kH);
  ASSERT_FALSE(frame.ok());
  expect_invalid(frame.error(), "Renderer::render", "DtSettings.alpha_start: must be at least 0 and below 1");
  const auto vis = renderer.visibility(cam, bad, kW, kH);
  ASSERT_FALSE(vis.ok());
  expect_invalid(vis.error(), "Renderer::visibility", "DtSettings.alpha_start");
  FrameSettings lens;
  lens.method = Method::lens;
  lens.lens.radius = -1.0f;
  const auto lens_frame = renderer.render_offscreen(cam, lens, kW, kH);
  ASSERT_FALSE(lens_frame.ok());
  expect_invalid(lens_frame.error(), "Renderer::render", "LensSettings.radius must be finite and > 0");
  FrameSettings colours;
  colours.flat_colors.assign(renderer.scene().objects.size() + 1, glm::vec3(1.0f));
  const auto flat = renderer.render_offscreen(cam, colours, kW, kH);
  ASSERT_FALSE(flat.ok());
  expect_invalid(flat.error(), "Renderer::render", "more flat colours than objects");
}

TEST(RenderErrors, ComparingImagesOfDifferentSizesIsAnError) {
  Image a{2, 1, std::vector<std::uint8_t>(8, 0)}, b{1, 2, std::vector<std::uint8_t>(8, 0)};
  const auto d = compare(a, b);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.error().kind, ErrorKind::invalid_input);
  EXPECT_TRUE(contains(d.error().message, "images differ in size (2x1 and 1x2)")) << d.error().message;
  const auto in = compare_in(a, a, std::vector<std::uint8_t>(3, 1));
  ASSERT_FALSE(in.ok());
  EXPECT_TRUE(contains(in.error().message, "not one byte per pixel")) << in.error().message;
  EXPECT_EQ(must(compare_in(a, a, std::vector<std::uint8_t>(2, 1))).pixels, 2);
}

// The test hook `dtlab run`'s render-failure test relies on: while the file exists every frame is
// an environment Error naming GL_OUT_OF_MEMORY; once it is gone frames render again.
TEST(RenderErrors, TheInjectedOutOfMemoryFailsFramesOnlyWhileItsFileExists) {
  testing::headless_context();
  const std::filesystem::path flag =
      std::filesystem::temp_directory_path() / ("dtlab_render_fail_" + std::to_string(::getpid()));
  std::filesystem::remove(flag);
  ::setenv("DTLAB_TEST_RENDER_FAIL_FILE", flag.c_str(), 1);
  auto r = Renderer::create(occluded_target());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const Camera cam = front_camera(kW, kH);
  must((*r)->render_offscreen(cam, dt_fast(), kW, kH));
  { std::ofstream(flag) << "fail\n"; }
  const auto failed = (*r)->render_offscreen(cam, dt_fast(), kW, kH);
  const auto vis = (*r)->visibility(cam, dt_fast(), kW, kH);
  std::filesystem::remove(flag);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().kind, ErrorKind::environment);
  EXPECT_TRUE(contains(failed.error().message, "the GL ran out of memory")) << failed.error().message;
  EXPECT_TRUE(contains(failed.error().message, "GL_OUT_OF_MEMORY (injected")) << failed.error().message;
  ASSERT_FALSE(vis.ok()) << "visibility renders frames: it fails with them";
  EXPECT_EQ(vis.error().kind, ErrorKind::environment);
  EXPECT_TRUE(contains(vis.error().message, "Renderer::render: the GL ran out of memory")) << vis.error().message;
  const auto again = (*r)->render_offscreen(cam, dt_fast(), kW, kH);
  EXPECT_TRUE(again.ok()) << again.error().to_string();
  ::unsetenv("DTLAB_TEST_RENDER_FAIL_FILE");
}

}  // namespace
}  // namespace dtlab::render
