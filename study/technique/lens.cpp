// The lens method (Ropinski & Hinrichs 2004) in the registry: its key group
// (shape, style, radius, distance, length; the mode is the dt group's key,
// "fixed" or "active" here) and its registration. Guarantees: the lens keys'
// ranges and their conversion to LensSettings are written here only.
#include <array>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

namespace {

using Kind = KeySpec::Kind;
constexpr std::array<std::string_view, 4> kShapes{"sphere", "box", "cylinder", "cone"};
constexpr std::array<std::string_view, 3> kStyles{"eraser", "wireframe", "tint"};
constexpr std::array kLensKeys{
    KeySpec{"shape", Kind::choice, 0, 0, kShapes},
    KeySpec{"style", Kind::choice, 0, 0, kStyles},
    KeySpec{"radius", Kind::number, 0.001, 100000},  // world units
    KeySpec{"distance", Kind::number, 0.001, 100000},
    KeySpec{"length", Kind::number, 0.001, 100000},
};

// radius and distance are required with the lens (world units: the scene's own scale).
void parse_lens(KeyReader& r, const Technique& method, Keys& keys) {
  LensKeys& k = keys.lens;
  const bool lens = method.reads(Group::lens);
  if (auto v = r.choice(kLensKeys[0])) k.shape = *v;
  if (auto v = r.choice(kLensKeys[1])) k.style = *v;
  if (auto v = r.number(kLensKeys[2], lens)) k.radius = *v;
  if (auto v = r.number(kLensKeys[3], lens)) k.distance = *v;
  if (auto v = r.number(kLensKeys[4])) k.length = *v;
  warn_unread(r, method, group(Group::lens), "a lens key");
}

// Only with the lens: the design hash of every other protocol stays as it was.
void hash_lens(HashSink& c, const Technique& method, const Keys& keys) {
  if (!method.reads(Group::lens)) return;
  const LensKeys& k = keys.lens;
  c.str("shape", k.shape);
  c.str("style", k.style);
  c.num("radius", k.radius);
  c.num("distance", k.distance);
  c.num("length", k.length);
}

// At the view's centre; in active mode a responder moves it to the cursor (LensSettings::center).
std::optional<KeyProblem> lens_to_frame(const Technique&, const Keys& keys, int width, int height, MethodSettings& out) {
  const LensKeys& k = keys.lens;
  LensSettings& l = out.lens;
  const auto shape = parse_lens_shape(k.shape);
  if (!shape) return KeyProblem{"shape", "unknown lens shape '" + k.shape + "' (sphere, box, cylinder, cone)"};
  const auto style = parse_lens_style(k.style);
  if (!style) return KeyProblem{"style", "unknown lens style '" + k.style + "' (eraser, wireframe, tint)"};
  const std::string& mode = keys.dt.mode;
  if (mode != "active" && mode != "fixed")
    return KeyProblem{"mode", "a lens is 'active' (follows the cursor) or 'fixed', not '" + mode + "'"};
  l.shape = *shape;
  l.style = *style;
  l.center = {0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)};
  l.follows_cursor = mode == "active";
  l.radius = static_cast<float>(k.radius);
  l.distance = static_cast<float>(k.distance);
  l.length = static_cast<float>(k.length > 0.0 ? k.length : 2.0 * k.radius);
  if (const auto problem = check(l)) return KeyProblem{problem->substr(0, problem->find(' ')), *problem};
  return std::nullopt;
}

// The paper's claim: the cost does not depend on the lens's shape (two scene passes more than
// standard whatever the shape). The bench sizes each lens to its scene.
std::vector<BenchRow> lens_bench_rows(const MethodSettings& base) {
  std::vector<BenchRow> rows;
  for (auto [shape, style] : {std::pair{LensShape::sphere, LensStyle::eraser}, std::pair{LensShape::box, LensStyle::wireframe},
                              std::pair{LensShape::cone, LensStyle::tint}}) {
    BenchRow row{"lens " + std::string(to_string(shape)) + " " + std::string(to_string(style)), base};
    row.settings.lens.shape = shape;
    row.settings.lens.style = style;
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

extern const KeyGroup k_keys_lens{Group::lens, "lens", kLensKeys, parse_lens, hash_lens, lens_to_frame};

extern const Technique k_method_lens{
    .id = Method::lens,
    .name = "lens",
    .summary = "Ropinski & Hinrichs's volumetric 3D magic lens (a convex lens volume, a second depth test against "
               "its back- and front-face depth maps, three scene passes)",
    .groups = bit(Group::culling) | bit(Group::lens),
    .bench_rows = lens_bench_rows,
    .bench_default = false,  // its rows: three shapes
};

}  // namespace dtlab::technique
