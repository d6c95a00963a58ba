// Canonical serialization of a Scene; see hash.h for what is (not) included
// and why. The format is line-oriented ASCII; docs/scene.md shows a sample.
#include "study/scene/hash.h"

#include <cmath>
#include <stdexcept>
#include <string_view>

#include "study/common/hash.h"
#include "study/scene/generate.h"

namespace dtlab::scene {
namespace {

class Writer {
 public:
  Writer& word(std::string_view w) {
    sep();
    out_ += w;
    return *this;
  }
  Writer& integer(long long v) { return word(std::to_string(v)); }
  // A float as a whole number of 1e-4 units: exact for our deterministic values,
  // independent of how a platform prints floats.
  Writer& q(double v) {
    if (!std::isfinite(v) || std::abs(v) > 1e12) throw std::invalid_argument("canonical_serialization: non-finite or huge value");
    return integer(std::llround(v * 1e4));
  }
  Writer& vec(const glm::vec3& v) { return q(v.x).q(v.y).q(v.z); }
  void end() {
    out_ += '\n';
    fresh_ = true;
  }
  std::string take() { return std::move(out_); }

 private:
  void sep() {
    if (!fresh_) out_ += ' ';
    fresh_ = false;
  }
  std::string out_;
  bool fresh_ = true;
};

}  // namespace

std::string canonical_serialization(const Scene& s) {
  Writer w;
  w.word("dtlab-scene").integer(kSceneFormatVersion).end();
  w.word("scene").word(kind_name(s.kind)).word(task_name(s.task)).word(std::to_string(s.seed)).end();
  for (const Mesh& m : s.meshes)
    w.word("mesh").word(m.name).integer(static_cast<long long>(m.vertices.size())).integer(static_cast<long long>(m.triangle_count())).end();
  for (const Object& o : s.objects) {
    w.word("object").integer(o.id).word(o.kind).integer(o.mesh).vec(o.color);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) w.q(o.transform[c][r]);
    w.integer(o.target).integer(o.impenetrable).integer(o.group).integer(o.order_in_group).end();
  }
  const Answer& a = s.answer;
  w.word("answer").word(task_name(a.task)).integer(a.count).integer(static_cast<unsigned char>(a.letter))
      .q(a.position.x).q(a.position.y).word(a.target_kind.empty() ? "-" : a.target_kind).end();
  const CameraStart& c = s.camera;
  w.word("camera").word(c.mode == CameraStart::Mode::orbit ? "orbit" : "walk").vec(c.target).vec(c.position)
      .q(c.yaw).q(c.pitch).q(c.fov_y).end();
  w.word("bounds").vec(s.bounds_min).vec(s.bounds_max).end();
  if (s.plan) {
    const FloorPlan& p = *s.plan;
    w.word("plan").integer(p.width).integer(p.height).q(p.cell_size).end();
    w.word("rooms");
    for (int r : p.room) w.integer(r);
    w.end();
    for (const auto& d : p.doors) w.word("door").integer(d.x0).integer(d.y0).integer(d.x1).integer(d.y1).end();
  }
  return w.take();
}

std::string scene_hash(const Scene& scene) { return sha256_hex(canonical_serialization(scene)); }

}  // namespace dtlab::scene
