// Dynamic transparency (Elmqvist, Assarsson & Tsigas 2008) in the registry:
// the methods standard, dt-seed, dt-fast and reference, and the key groups
// dt (the visual model's keys), culling (every method) and guard (the R1
// guard). Guarantees: the keys' ranges and the protocol-to-frame conversion
// of the dynamic transparency keys are written here only. Never: GL.
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

namespace {

using Kind = KeySpec::Kind;
constexpr std::array<std::string_view, 3> kMaskShapes{"outline", "circle", "ellipse"};
constexpr std::array<std::string_view, 3> kModes{"passive", "active", "fixed"};
// a0 and aT stop short of 1 (the renderer refuses an opaque "transparent" surface, and a value
// closer to 1 than 2^-25 becomes 1 in the renderer's single precision).
constexpr std::array kDtKeys{
    KeySpec{"a0", Kind::number, 0, 0.99},
    KeySpec{"aT", Kind::number, 0, 0.99},
    KeySpec{"gradient_width", Kind::integer, 0, 64},
    KeySpec{"mask_resolution", Kind::integer, 16, 4096},
    KeySpec{"mask_shape", Kind::choice, 0, 0, kMaskShapes},
    KeySpec{"mode", Kind::choice, 0, 0, kModes},
    KeySpec{"layer_limit", Kind::integer, 0, 60},
    KeySpec{"searchlight_radius", Kind::number, 0.01, 2},  // share of the view's height (2: the whole view)
};
constexpr std::array kCullingKeys{KeySpec{"occlusion_culling", Kind::boolean}};
constexpr std::array kGuardKeys{KeySpec{"r1_guard", Kind::boolean}};

// What each mode means, for messages.
std::string mode_phrase(std::string_view mode) {
  const char* what = mode == "passive" ? "the whole view" : mode == "active" ? "follows the cursor" : "at the view's centre";
  return "\"" + std::string(mode) + "\" (" + what + ")";
}

// The modes `method` takes: a searchlight method passive (its default) or active, a lens active
// or fixed (its default); none otherwise.
std::vector<std::string_view> modes_of(const Technique& method) {
  if (method.searchlight) return {"passive", "active"};
  if (method.reads(Group::lens)) return {"active", "fixed"};
  return {};
}

void parse_mode(KeyReader& r, const Technique& method, DtKeys& k) {
  const std::vector<std::string_view> modes = modes_of(method);
  if (modes.empty() && k.mode == "fixed" && r.has("mode")) {
    r.error("mode", "\"fixed\" is a lens mode (method = \"lens\"); method = \"" + std::string(method.name) +
                        "\" has no mode");
    return;
  }
  if (modes.empty()) {
    if (r.has("mode"))
      r.warning("mode", "has no effect with method = \"" + std::string(method.name) + "\" (" +
                            (method.groups == bit(Group::culling) ? "no transparency" : "no searchlight") + ")");
    return;
  }
  if (!r.has("mode")) {
    k.mode = method.searchlight ? "passive" : "fixed";
    return;
  }
  if (std::find(modes.begin(), modes.end(), k.mode) != modes.end()) return;
  std::string owners;
  for (const Technique* t : all())
    if (const auto m = modes_of(*t); std::find(m.begin(), m.end(), k.mode) != m.end() && t->reads(Group::lens))
      owners = " (\"" + k.mode + "\" is a lens mode, method = \"" + std::string(t->name) + "\")";
  r.error("mode", "with method = \"" + std::string(method.name) + "\" expected " + mode_phrase(modes[0]) + " or " +
                      mode_phrase(modes[1]) + ", not \"" + k.mode + "\"" + owners);
}

void parse_dt(KeyReader& r, const Technique& method, Keys& keys) {
  DtKeys& k = keys.dt;
  if (auto v = r.number(kDtKeys[0])) k.a0 = *v;
  if (auto v = r.number(kDtKeys[1])) k.aT = *v;
  if (auto v = r.integer(kDtKeys[2])) k.gradient_width = static_cast<int>(*v);
  if (auto v = r.integer(kDtKeys[3])) k.mask_resolution = static_cast<int>(*v);
  if (auto v = r.choice(kDtKeys[4])) k.mask_shape = *v;
  if (auto v = r.choice(kDtKeys[5])) k.mode = *v;
  if (auto v = r.integer(kDtKeys[6])) k.layer_limit = static_cast<int>(*v);
  if (auto v = r.number(kDtKeys[7])) k.searchlight_radius = *v;
  static constexpr std::array<std::string_view, 2> kOwnChecks{"mode", "searchlight_radius"};
  warn_unread(r, method, group(Group::dt), "no dynamic transparency", kOwnChecks);
  parse_mode(r, method, k);
  if (method.reads(Group::dt) && k.a0 > k.aT)
    r.warning("a0", "a0 > aT: the gradient starts more opaque than the surfaces in front of the target "
                    "(the reference design uses a low a0 and a higher aT)");
  if (r.has("searchlight_radius") && (k.mode != "active" || !method.searchlight))
    r.warning("searchlight_radius", "has no effect without a searchlight (dynamic transparency with mode = \"active\")");
}

// Every protocol's hash holds the dynamic transparency keys, whatever its method (as it always
// has); the searchlight's radius only when not the default, so that every protocol written before
// the key keeps its hash (their searchlight was 120 pixels, the default's size at 800 x 600).
void hash_dt(HashSink& c, const Technique&, const Keys& keys) {
  const DtKeys& k = keys.dt;
  c.num("a0", k.a0);
  c.num("aT", k.aT);
  c.integer("gradient_width", k.gradient_width);
  c.integer("mask_resolution", k.mask_resolution);
  c.str("mask_shape", k.mask_shape);
  c.str("mode", k.mode);
  c.integer("layer_limit", k.layer_limit);
  if (k.searchlight_radius != DtKeys{}.searchlight_radius) c.num("searchlight_radius", k.searchlight_radius);
}

std::optional<KeyProblem> dt_to_frame(const Technique&, const Keys& keys, int width, int height, MethodSettings& out) {
  const DtKeys& k = keys.dt;
  DtSettings& dt = out.dt;
  const auto shape = parse_mask_shape(k.mask_shape);
  if (!shape) return KeyProblem{"mask_shape", "unknown mask shape '" + k.mask_shape + "' (outline, circle, ellipse)"};
  dt.alpha_start = static_cast<float>(k.a0);
  dt.alpha_target = static_cast<float>(k.aT);
  // A mask finer than this view can show is the view's own resolution (0: one texel per pixel):
  // the same picture, at less cost. The gradient keeps the width the protocol's mask gives it.
  dt.mask_resolution = k.mask_resolution > max_mask_resolution(width, height) ? 0 : k.mask_resolution;
  dt.gradient_px =
      gradient_px_from_mask_pixels(static_cast<float>(k.gradient_width), k.mask_resolution, width, height);
  dt.shape = *shape;
  if (k.mode == "passive") {
    dt.mode = DtMode::passive;
  } else if (k.mode == "active") {
    dt.mode = DtMode::active;
    dt.searchlight_center = {0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height)};
    dt.searchlight_radius = static_cast<float>(k.searchlight_radius) * static_cast<float>(height);
  } else {
    return KeyProblem{"mode", "unknown mode '" + k.mode + "' (passive, active)"};
  }
  dt.layer_limit = k.layer_limit;
  // The renderer's checks (ranges), each named by the protocol key the author wrote.
  if (const auto problem = check(dt, width, height)) {
    const char* key = "";
    switch (problem->field) {
      case DtField::alpha_target: key = "aT"; break;
      case DtField::alpha_start: key = "a0"; break;
      case DtField::gradient: key = "gradient_width"; break;
      case DtField::mask_resolution: key = "mask_resolution"; break;
      case DtField::layer_limit: key = "layer_limit"; break;
      case DtField::searchlight: key = "searchlight_radius"; break;
    }
    return KeyProblem{key, problem->message + " (at a " + std::to_string(width) + "x" + std::to_string(height) +
                               " viewport)"};
  }
  return std::nullopt;
}

void parse_culling(KeyReader& r, const Technique&, Keys& keys) {
  if (auto v = r.boolean(kCullingKeys[0])) keys.culling.occlusion_culling = *v;
}
void hash_culling(HashSink& c, const Technique&, const Keys& keys) {
  if (keys.culling.occlusion_culling) c.str("occlusion_culling", "true");  // unset: the hash stays as it was
}

void parse_guard(KeyReader& r, const Technique& method, Keys& keys) {
  if (auto v = r.boolean(kGuardKeys[0])) keys.guard.r1_guard = *v;
  warn_unread(r, method, group(Group::guard), "no dynamic transparency");
}
void hash_guard(HashSink& c, const Technique&, const Keys& keys) {
  if (!keys.guard.r1_guard) c.str("r1_guard", "false");  // on (the default): the hash stays as it was
}
std::optional<KeyProblem> guard_to_frame(const Technique&, const Keys& keys, int, int, MethodSettings& out) {
  // The protocol's r1_guard (on unless it says false); the renderer's own default is the
  // article's algorithm as printed, under which a target in a farther target's gradient fades to a0.
  out.dt.r1_guard = keys.guard.r1_guard;
  return std::nullopt;
}

// `dtlab bench`'s extra rows of a dynamic transparency method: the R1 guard on (the protocol
// default) beside the article's algorithm as printed.
std::vector<BenchRow> dt_bench_rows(const MethodSettings& base) {
  BenchRow guard{std::string(to_string(base.method)) + " R1 guard", base};
  guard.settings.dt.r1_guard = true;
  return {guard};
}

// dt-seed dilates each target's mask n + 2 times at R x R (docs/render.md, dt-seed's mask passes).
double seed_mask_texels(const Keys& keys, long long targets) {
  const double r = static_cast<double>(keys.dt.mask_resolution);
  return static_cast<double>(targets) * static_cast<double>(keys.dt.gradient_width + 2) * r * r;
}

constexpr unsigned kDynamicTransparency = bit(Group::dt) | bit(Group::culling) | bit(Group::guard);

}  // namespace

extern const KeyGroup k_keys_dt{Group::dt, "dt", kDtKeys, parse_dt, hash_dt, dt_to_frame};
extern const KeyGroup k_keys_culling{Group::culling, "culling", kCullingKeys, parse_culling, hash_culling, nullptr};
extern const KeyGroup k_keys_guard{Group::guard, "guard", kGuardKeys, parse_guard, hash_guard, guard_to_frame};

extern const Technique k_method_standard{
    .id = Method::standard,
    .name = "standard",
    .summary = "opaque z-buffered rendering with a headlight",
    .groups = bit(Group::culling),
};
extern const Technique k_method_dt_seed{
    .id = Method::dt_seed,
    .name = "dt-seed",
    .summary = "the article's image-space dynamic transparency, faithfully (object-level back-to-front order, "
               "per-target masks grown by ping-pong border passes)",
    .groups = kDynamicTransparency,
    .target_masks = true,
    .searchlight = true,
    .bench_rows = dt_bench_rows,
    .mask_texels = seed_mask_texels,
};
extern const Technique k_method_dt_fast{
    .id = Method::dt_fast,
    .name = "dt-fast",
    .summary = "the same visual model at close to standard's cost (all masks at once in a reduced-resolution atlas, "
               "scissored regions)",
    .groups = kDynamicTransparency,
    .target_masks = true,
    .searchlight = true,
    .approximates = Method::dt_seed,
    .bench_rows = dt_bench_rows,
};
extern const Technique k_method_reference{
    .id = Method::reference,
    .name = "reference",
    .summary = "exact per-pixel compositing of dynamic transparency on the CPU (the error yardstick)",
    .groups = kDynamicTransparency,
    .target_masks = true,
    .searchlight = true,
    .bench_default = false,
};

}  // namespace dtlab::technique
