// Hand-built scenes for the render tests: axis-aligned quads and boxes whose
// screen positions and colours are known, so a test can derive the expected
// pixel from the blending equations (docs/render.md) instead of from earlier
// output. Also the shared headless GL context of a test program.
#pragma once
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "app/platform/gl_context.h"
#include "study/render/render.h"
#include "study/scene/scene.h"

namespace dtlab::render::testing {

// The process's headless context (created on first use, current on return); aborts the
// test program with a message if OSMesa cannot give GL 3.3 core.
platform::GlContext& headless_context();

// A quad in the plane z = `z` spanning [x0, x1] x [y0, y1], facing +z.
scene::Mesh quad_mesh(float x0, float y0, float x1, float y1, float z);
// An axis-aligned box with corners `lo` and `hi` (12 triangles, outward normals).
scene::Mesh box_mesh(glm::vec3 lo, glm::vec3 hi);
// A UV sphere of `radius` around `center` (stacks x slices quads).
scene::Mesh sphere_mesh(glm::vec3 center, float radius, int stacks = 16, int slices = 24);

// Adds `mesh` as a new object (id = index + 1) and returns its index.
std::uint32_t add_object(scene::Scene& s, scene::Mesh mesh, glm::vec3 color, bool target = false,
                         bool impenetrable = false);

// Camera at the origin looking down -z with a 60 degree vertical field of view.
Camera front_camera(int width, int height);

// Window pixel (bottom-left origin, GL) of world point p under `camera`.
glm::vec2 project(const Camera& camera, glm::vec3 p, int width, int height);

// RGB of pixel (x, y) with y counted from the bottom (GL), 0..255.
glm::ivec3 rgb_at(const Image& img, int x, int y_from_bottom);
int alpha_at(const Image& img, int x, int y_from_bottom);

// With DTLAB_TEST_PNG_DIR set, writes `img` there as <suite>.<test>[-suffix].png (for eyes only).
void maybe_dump(const Image& img, const std::string& suffix = "");

}  // namespace dtlab::render::testing
