// The ghosting method's passes (docs/render.md, "ghosting"): the distractors
// in front of a target in view (after it in the back-to-front order, their
// screen rectangles overlapping its silhouette's) are ghosts. `ghost-opaque`
// draws every other object in view z-buffered, as `opaque` does; `ghost-blend`
// draws the ghosts back to front, front faces only, depth-tested but not
// written, blended at GhostingSettings::alpha over that (shaders/ghost.frag,
// compiled here on first use), then their edges as opaque lines: silhouette
// edges (Appel's test, one face towards the eye and one away), outline edges
// and creases (faces meeting at more than 30 degrees) between faces towards
// the eye. Guarantees: with no ghost in view the frame is standard's. Never:
// a target or an impenetrable surface drawn as a ghost.
#include <glad/gl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "study/render/detail/method.h"
#include "study/render/detail/passes.h"
#include "study/render/detail/vdt_alpha.h"

namespace dtlab::render::detail {

namespace {

const float kCrease = std::cos(glm::radians(30.0f));  // faces meeting at more than this angle: a crease
const glm::vec3 kEdgeColor{0.08f, 0.08f, 0.1f};

// The ghost program, the edge line buffer, the meshes' edge lists and this frame's ghosts (the
// passes read them when they run).
class GhostState final : public MethodState {
 public:
  ~GhostState() override {
    delete_program(program);
    if (vao != 0) glDeleteVertexArrays(1, &vao);
    if (vbo != 0) glDeleteBuffers(1, &vbo);
  }
  Program program;
  unsigned vao = 0, vbo = 0;
  std::vector<std::optional<VdtTopology>> topology;  // per mesh, built on first use
  std::vector<bool> ghost;                           // per object
  std::vector<std::uint32_t> ghosts;                 // back to front
  std::vector<glm::vec3> lines;                      // this frame's edges, world space, two points each
};

// Distractors after a target in the back-to-front order whose rectangles overlap its silhouette's.
void find_ghosts(const FrameContext& fc, GhostState& s) {
  const auto& objects = fc.gpu.objects();
  s.ghost.assign(objects.size(), false);
  s.ghosts.clear();
  std::vector<PixelRect> behind;  // silhouettes of the targets met so far, back to front
  for (std::uint32_t i : fc.view.sorted) {
    const int slot = fc.view.target_slot[i];
    if (slot >= 0) {
      behind.push_back(fc.view.targets[static_cast<std::size_t>(slot)].rect);
      continue;
    }
    if (objects[i].impenetrable || !objects[i].drawable()) continue;
    for (const PixelRect& t : behind)
      if (t.overlaps(fc.view.rects[i])) {
        s.ghost[i] = true;
        s.ghosts.push_back(i);
        break;
      }
  }
}

// The edges of every ghost as seen from the eye, into s.lines (world space).
void find_edges(const FrameContext& fc, GhostState& s) {
  s.lines.clear();
  if (s.topology.size() != fc.scene.meshes.size()) s.topology.assign(fc.scene.meshes.size(), std::nullopt);
  for (std::uint32_t i : s.ghosts) {
    const ObjectRecord& o = fc.gpu.objects()[i];
    std::optional<VdtTopology>& topo = s.topology[o.mesh];
    if (!topo) topo = vdt_topology(fc.scene.meshes[o.mesh]);
    const glm::vec3 eye = glm::vec3(glm::inverse(o.model) * glm::vec4(fc.view.camera.eye, 1.0f));
    const auto towards = [&](std::uint32_t f) { return glm::dot(glm::vec3(topo->planes[f]), eye) + topo->planes[f].w > 0.0f; };
    for (const VdtTopology::Edge& e : topo->edges) {
      bool edge = false;
      if (e.faces.size() != 2) {
        edge = !e.faces.empty() && towards(e.faces[0]);  // an outline edge of an open surface
      } else {
        const bool a = towards(e.faces[0]), b = towards(e.faces[1]);
        edge = a != b || (a && glm::dot(glm::vec3(topo->planes[e.faces[0]]), glm::vec3(topo->planes[e.faces[1]])) < kCrease);
      }
      if (!edge) continue;
      s.lines.push_back(glm::vec3(o.model * glm::vec4(topo->points[e.a], 1.0f)));
      s.lines.push_back(glm::vec3(o.model * glm::vec4(topo->points[e.b], 1.0f)));
    }
  }
}

void begin_pass(const FrameContext& fc, unsigned framebuffer) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, fc.width(), fc.height());
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
}

// The edge lines, opaque, depth-tested against the opaque objects (ghosts write no depth).
void draw_edges(const FrameContext& fc, GhostState& s) {
  if (s.lines.empty()) return;
  if (s.vao == 0) {
    glGenVertexArrays(1, &s.vao);
    glGenBuffers(1, &s.vbo);
    glBindVertexArray(s.vao);
    glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  }
  glBindVertexArray(s.vao);
  glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.lines.size() * sizeof(glm::vec3)), s.lines.data(),
               GL_STREAM_DRAW);
  const Program& p = s.program;
  const glm::mat4 identity(1.0f);
  const glm::mat3 normal(1.0f);
  // Weight frames: a ghost's edges weigh as the ghost (its flat colour); else the edge colour.
  const glm::vec4 flat = fc.settings.flat_colors.empty() ? glm::vec4(kEdgeColor, 1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  glUniformMatrix4fv(p.loc("u_model"), 1, GL_FALSE, glm::value_ptr(identity));
  glUniformMatrix3fv(p.loc("u_normal_matrix"), 1, GL_FALSE, glm::value_ptr(normal));
  glUniform4fv(p.loc("u_flat"), 1, glm::value_ptr(flat));
  glUniform1f(p.loc("u_alpha"), 1.0f);
  glDepthFunc(GL_LEQUAL);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(s.lines.size()));
  glBindVertexArray(fc.gpu.vao());
}

void draw_ghosts(const FrameContext& fc, GhostState& s) {
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // colour only; alpha stays
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  const Program& p = s.program;
  fc.use_program(p);
  fc.bound.lit = &p;
  glUniformMatrix4fv(p.loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(fc.view.view_proj));
  glUniform3fv(p.loc("u_eye"), 1, glm::value_ptr(fc.view.camera.eye));
  glUniform1f(p.loc("u_alpha"), fc.settings.ghosting.alpha);
  for (std::uint32_t i : s.ghosts) {
    glFrontFace(fc.gpu.objects()[i].mirrored ? GL_CW : GL_CCW);
    fc.draw_lit(i);
  }
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  if (fc.settings.ghosting.edges) draw_edges(fc, s);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

Handle add_ghost_passes(FrameGraph& fg, const FrameContext& fc, GhostState& s) {
  struct GhostPassData {
    Handle color, depth;
  };
  const auto& opaque = fg.add_pass<GhostPassData>(
      "ghost-opaque",
      [&](FrameGraph::Builder& b, GhostPassData& d) {
        d.color = b.write(b.create("color", {fc.width(), fc.height(), fc.color_format, false}));
        d.depth = b.write(b.create("depth", {fc.width(), fc.height(), TextureFormat::depth24_stencil8, false}));
      },
      [&fc, &s](const GhostPassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDepthMask(GL_TRUE);
        clear_to_background(fc);
        fc.use_lit(fc.view.view_proj);
        for (std::uint32_t i = 0; i < fc.view.rects.size(); ++i)
          if (!fc.view.rects[i].empty() && !s.ghost[i]) fc.draw_lit(i);
      });
  const auto& blend = fg.add_pass<GhostPassData>(
      "ghost-blend",
      [&](FrameGraph::Builder& b, GhostPassData& d) {
        d.color = b.write(b.read(opaque.color));  // drawn over the opaque objects
        d.depth = b.write(b.read(opaque.depth));
      },
      [&fc, &s](const GhostPassData& d, PassResources& r) {
        begin_pass(fc, r.framebuffer({d.color}, d.depth));
        draw_ghosts(fc, s);
      });
  return blend.color;
}

MethodFrame add_ghosting(FrameGraph& fg, const FrameContext& fc, MethodSlot& slot) {
  if (!slot.state) {
    auto state = std::make_unique<GhostState>();
    state->program = link_method_program("ghosting", "object.vert", "ghost.frag", "", "lighting.glsl");
    slot.state = std::move(state);
  }
  auto& s = static_cast<GhostState&>(*slot.state);
  find_ghosts(fc, s);
  if (s.ghosts.empty()) return add_standard_first(fg, fc, nullptr);  // nothing in front of a target
  if (fc.settings.ghosting.edges) find_edges(fc, s);
  return {add_ghost_passes(fg, fc, s), {}};
}

}  // namespace

extern const MethodPasses k_passes_ghosting{nullptr, add_ghosting};

}  // namespace dtlab::render::detail
