// Shader programs (study/render/detail/programs.h): the shared GLSL chunks
// (lighting.glsl, searchlight.glsl) are written once and put before the code
// that names them; the driver's log points at the right file and line
// through the #line directives (the file's own line numbers; line i of chunk
// k as 10000 k + i, whatever the driver does with #line's source number); a
// missing shader or chunk is an environment Error naming the file; a method's
// own program that fails to link fails the frame with an environment Error
// naming the method, the shader file and the driver's log.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "study/render/detail/boundary.h"
#include "study/render/detail/programs.h"
#include "study/render/render.h"
#include "tests/common/must.h"
#include "tests/render/scenes.h"

namespace dtlab::embedded {
std::string_view shaders(std::string_view name);
std::vector<std::string_view> shaders_names();
}  // namespace dtlab::embedded

namespace dtlab::render::detail {
namespace {

bool contains(std::string_view text, std::string_view part) { return text.find(part) != std::string_view::npos; }

// The 1-based number of the first line of `text` that contains `part` (0: none).
int line_of(std::string_view text, std::string_view part) {
  const auto at = text.find(part);
  if (at == std::string_view::npos) return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

// The driver's log of compiling `source` as a fragment shader; empty if it compiles.
std::string compile_log(const std::string& source) {
  const GLuint s = glCreateShader(GL_FRAGMENT_SHADER);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0, n = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  glGetShaderiv(s, GL_INFO_LOG_LENGTH, &n);
  std::string log(static_cast<std::size_t>(n > 0 ? n : 1), '\0');
  glGetShaderInfoLog(s, n, nullptr, log.data());
  glDeleteShader(s);
  return ok != 0 ? std::string() : log;
}

// The lighting formula has one home: the chunk defines headlight() and no shader file repeats its
// maths (a regression guard: ghost.frag, lens and screen-door's variants once carried copies).
TEST(ShaderPrograms, TheLightingIsWrittenOnceInItsChunk) {
  const std::string_view chunk = embedded::shaders("lighting.glsl");
  ASSERT_FALSE(chunk.empty()) << "lighting.glsl is not embedded";
  EXPECT_TRUE(contains(chunk, "vec3 headlight("));
  EXPECT_TRUE(contains(chunk, "0.3 + 0.7"));
  int callers = 0;
  for (std::string_view name : embedded::shaders_names()) {
    if (name == "lighting.glsl") continue;
    SCOPED_TRACE(std::string(name));
    const std::string_view text = embedded::shaders(name);
    EXPECT_FALSE(contains(text, "0.3 + 0.7"));
    EXPECT_FALSE(contains(text, "vec3 headlight("));
    callers += contains(text, "headlight(") ? 1 : 0;
  }
  EXPECT_EQ(callers, 5);  // object, ghost, lens, screen_door, vdt
}

// The searchlight cut has one home too: the chunk defines outside_searchlight(), and the shared
// shaders with a searchlight variant call it.
TEST(ShaderPrograms, TheSearchlightCutIsWrittenOnceInItsChunk) {
  const std::string_view chunk = embedded::shaders("searchlight.glsl");
  ASSERT_FALSE(chunk.empty()) << "searchlight.glsl is not embedded";
  EXPECT_TRUE(contains(chunk, "bool outside_searchlight(vec3 s)"));
  EXPECT_TRUE(contains(chunk, "distance(gl_FragCoord.xy, s.xy) > s.z"));
  for (const char* name : {"object.frag", "flat_alpha.frag", "shape.frag"}) {
    SCOPED_TRACE(name);
    const std::string_view text = embedded::shaders(name);
    EXPECT_TRUE(contains(text, "outside_searchlight(u_searchlight)"));
    EXPECT_FALSE(contains(text, "bool outside_searchlight("));
    EXPECT_FALSE(contains(text, "distance(gl_FragCoord.xy, u_searchlight.xy)"));
  }
}

// The assembled text: the file's #version line, the defines, the chunk after `#line 10001 1`,
// then `#line n 0` followed by line n of the file itself.
TEST(ShaderPrograms, TheSourcePutsTheDefinesAndTheChunkAfterTheVersionLine) {
  const std::string_view file = embedded::shaders("ghost.frag");
  const auto src = shader_source("ghost.frag", "A B", "lighting.glsl");
  ASSERT_TRUE(src.ok()) << src.error().to_string();
  const std::string& s = *src;
  const int version = line_of(file, "#version 330 core");
  ASSERT_GT(version, 0);
  const std::string head = "#version 330 core\n#define A\n#define B\n#line 10001 1\n";
  ASSERT_TRUE(contains(s, head));
  const std::string tail = "\n#line " + std::to_string(version + 1) + " 0\n";
  const auto at = s.find(tail);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(s.substr(s.find(head) + head.size(), embedded::shaders("lighting.glsl").size()),
            embedded::shaders("lighting.glsl"));
  // What follows `#line n 0` is the file from its line n on, unchanged.
  const std::string_view rest = file.substr(file.find("#version 330 core\n") + 18);
  EXPECT_EQ(s.substr(at + tail.size()), rest);
  // No defines and no chunks: the file as it is.
  EXPECT_EQ(*shader_source("ghost.frag"), std::string(file));
}

// An error in the file is reported at its own line, one in the chunk at 10000 + the chunk's line:
// the #line directives survive the driver's preprocessor. (Mesa prints source 0 for both, which
// is why chunk lines are numbered apart rather than told by #line's source number.)
TEST(ShaderPrograms, TheDriversLogPointsAtTheFileAndTheChunkLine) {
  testing::headless_context();
  const auto src = shader_source("object.frag", "", "lighting.glsl");
  ASSERT_TRUE(src.ok()) << src.error().to_string();
  ASSERT_EQ(compile_log(*src), "");

  const std::string_view file = embedded::shaders("object.frag");
  const int main_line = line_of(file, "void main() {");
  ASSERT_GT(main_line, 0);
  std::string broken = *src;
  broken.replace(broken.find("void main() {"), 13, "void main() { undeclared_in_file = 1.0;");
  const std::string log = compile_log(broken);
  EXPECT_TRUE(contains(log, ":" + std::to_string(main_line) + "(")) << log;

  const std::string_view chunk = embedded::shaders("lighting.glsl");
  const int chunk_line = line_of(chunk, "float le = length(to_eye);");
  ASSERT_GT(chunk_line, 0);
  broken = *src;
  broken.replace(broken.find("float le = length(to_eye);"), 26, "float le = undeclared_in_chunk;");
  const std::string chunk_log = compile_log(broken);
  EXPECT_TRUE(contains(chunk_log, ":" + std::to_string(10000 + chunk_line) + "(")) << chunk_log;
}

// A shader or chunk this build does not embed: an environment Error naming the file at fault.
TEST(ShaderPrograms, AMissingShaderOrChunkIsAnEnvironmentErrorNamingTheFile) {
  testing::headless_context();
  const auto chunk = link_program("object.vert", "object.frag", "", "no_such_chunk.glsl");
  ASSERT_FALSE(chunk.ok());
  EXPECT_EQ(chunk.error().kind, ErrorKind::environment);
  EXPECT_EQ(chunk.error().file, "shaders/object.frag");
  EXPECT_TRUE(contains(chunk.error().message, "no_such_chunk.glsl")) << chunk.error().message;

  const auto shader = link_program("object.vert", "no_such.frag");
  ASSERT_FALSE(shader.ok());
  EXPECT_EQ(shader.error().kind, ErrorKind::environment);
  EXPECT_EQ(shader.error().file, "shaders/no_such.frag");
}

// A method's program: linked, or a GlFailure (the renderer's public function returns it as an
// environment Error) whose text starts with the method's name and the shader file.
TEST(ShaderPrograms, AMethodsProgramThatFailsThrowsAGlFailureLedByTheMethod) {
  testing::headless_context();
  Program p = link_method_program("ghosting", "object.vert", "ghost.frag", "", "lighting.glsl");
  EXPECT_NE(p.id, 0u);
  EXPECT_GE(p.loc("u_alpha"), 0);
  delete_program(p);
  EXPECT_EQ(p.id, 0u);
  try {
    link_method_program("ghosting", "object.vert", "ghost.frag");  // headlight() undeclared without its chunk
    FAIL() << "no GlFailure";
  } catch (const GlFailure& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("ghosting: shaders/ghost.frag: does not compile: ", 0), 0u) << what;
    EXPECT_TRUE(contains(what, "headlight")) << what;
  }
  // An error inside the chunk (a define that empties the function's name): the message says how
  // its lines are numbered, and the log gives the chunk's line 7 as 10007.
  const int name_line = line_of(embedded::shaders("lighting.glsl"), "vec3 headlight(");
  ASSERT_GT(name_line, 0);
  try {
    link_method_program("ghosting", "object.vert", "ghost.frag", "headlight", "lighting.glsl");
    FAIL() << "no GlFailure";
  } catch (const GlFailure& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "shaders/ghost.frag: does not compile (line 10000 + i: line i of lighting.glsl)"))
        << what;
    EXPECT_TRUE(contains(what, ":" + std::to_string(10000 + name_line) + "(")) << what;
  }
}

// A target behind a distractor quad, in front of a far wall: every method's own programs are
// needed (the lens always, vdt's for the distractors, screen-door's and ghosting's for the
// occluded target).
scene::Scene occluded_target() {
  scene::Scene s;
  testing::add_object(s, testing::quad_mesh(-30, -30, 30, 30, -25), {0.2f, 0.8f, 0.3f});
  testing::add_object(s, testing::box_mesh({-1, -1, -14}, {1, 1, -12}), {1, 0, 0}, true);
  testing::add_object(s, testing::quad_mesh(-3, -3, 3, 3, -8), {0.1f, 0.3f, 0.9f});
  return s;
}

// End to end, with the test builds' hook that makes the driver refuse one shader: a method's own
// program that does not compile fails the frame that first needs it with an environment Error
// (field render) naming the method and the shader and carrying the driver's log; it links on a
// later frame, whose image equals a fresh renderer's. A shared program's failure fails
// Renderer::create the same way.
TEST(ShaderPrograms, AMethodsShaderThatTheDriverRefusesIsAnEnvironmentErrorOfTheFrame) {
  testing::headless_context();
  constexpr int kW = 64, kH = 48;
  const Camera cam = testing::front_camera(kW, kH);
  struct Case {
    Method method;
    const char* file;
  };
  for (const Case c : {Case{Method::lens, "lens.frag"}, Case{Method::vdt, "vdt_peel.frag"},
                       Case{Method::vdt, "vdt.frag"}, Case{Method::screen_door, "screen_door.frag"},
                       Case{Method::screen_door, "sd_resolve.frag"}, Case{Method::ghosting, "ghost.frag"}}) {
    SCOPED_TRACE(c.file);
    FrameSettings f;
    f.method = c.method;
    auto r = Renderer::create(occluded_target());
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ::setenv("DTLAB_TEST_SHADER_FAIL", c.file, 1);
    const auto failed = (*r)->render_offscreen(cam, f, kW, kH);
    ::unsetenv("DTLAB_TEST_SHADER_FAIL");
    ASSERT_FALSE(failed.ok()) << "the frame rendered without " << c.file;
    EXPECT_EQ(failed.error().kind, ErrorKind::environment) << failed.error().to_string();
    EXPECT_EQ(failed.error().field, "render");
    const std::string lead = "Renderer::render: " + std::string(technique::of(c.method).name) + ": shaders/" +
                             c.file + ": does not compile";
    EXPECT_EQ(failed.error().message.rfind(lead, 0), 0u) << failed.error().message;
    EXPECT_TRUE(contains(failed.error().message, "injected: $DTLAB_TEST_SHADER_FAIL")) << failed.error().message;

    test::must((*r)->render_offscreen(cam, f, kW, kH));
    const Image after = test::must((*r)->read_color());
    auto fresh = Renderer::create(occluded_target());
    ASSERT_TRUE(fresh.ok());
    test::must((*fresh)->render_offscreen(cam, f, kW, kH));
    EXPECT_EQ(after.rgba, test::must((*fresh)->read_color()).rgba) << "the frame after the failure differs";
  }
  ::setenv("DTLAB_TEST_SHADER_FAIL", "object.frag", 1);
  const auto shared = Renderer::create(occluded_target());
  ::unsetenv("DTLAB_TEST_SHADER_FAIL");
  ASSERT_FALSE(shared.ok());
  EXPECT_EQ(shared.error().kind, ErrorKind::environment);
  EXPECT_TRUE(contains(shared.error().to_string(), "shaders/object.frag")) << shared.error().to_string();
  EXPECT_EQ(shared.error().field, "render");  // docs/render.md, "Errors": every render.h Error's field
  EXPECT_EQ(shared.error().message.rfind("Renderer::create: ", 0), 0u) << shared.error().message;
}

}  // namespace
}  // namespace dtlab::render::detail
