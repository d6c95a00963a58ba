// The screen-door method (Poon 2000, chapter 4) in the registry: dt-seed's
// picture by sub-pixel screen-door transparency; it reads the dynamic
// transparency keys and its own (mask side, mask generation). Guarantees: the
// screen-door keys' ranges and conversion are written here only.
#include <array>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

namespace {

using Kind = KeySpec::Kind;
constexpr std::array<std::string_view, 3> kGenerations{"tabular", "pixel-tree", "white-noise"};
constexpr std::array kScreenDoorKeys{
    KeySpec{"screen_door_mask", Kind::integer, 8, 32, {}, "--screen-door-mask",
            "screen-door: mask side s (s x s sub-pixels): 8, 16 or 32 (default 8)"},
    KeySpec{"screen_door_generation", Kind::choice, 0, 0, kGenerations, "--screen-door-masks",
            "screen-door: mask generation (default tabular)"},
};

// It draws dt-seed's picture with exact target masks, so mask_resolution and layer_limit do not apply.
void parse_screen_door(KeyReader& r, const Technique& method, Keys& keys) {
  ScreenDoorKeys& k = keys.screen_door;
  if (auto v = r.integer(kScreenDoorKeys[0])) {
    if (*v == 8 || *v == 16 || *v == 32) k.screen_door_mask = static_cast<int>(*v);
    else
      r.error("screen_door_mask", "expected 8, 16 or 32 (the side of the mask in sub-pixels), got " + std::to_string(*v));
  }
  if (auto v = r.choice(kScreenDoorKeys[1])) k.screen_door_generation = *v;
  warn_unread(r, method, group(Group::screen_door), "a screen-door key");
  if (!method.reads(Group::screen_door)) return;
  for (const char* key : {"mask_resolution", "layer_limit"})
    if (r.has(key)) r.warning(key, "has no effect with method = \"screen-door\" (exact target masks, no layer limit)");
}

void hash_screen_door(HashSink& c, const Technique& method, const Keys& keys) {
  if (!method.reads(Group::screen_door)) return;  // only then: every other protocol's hash stays as it was
  c.integer("screen_door_mask", keys.screen_door.screen_door_mask);
  c.str("screen_door_generation", keys.screen_door.screen_door_generation);
}

std::optional<KeyProblem> screen_door_to_frame(const Technique&, const Keys& keys, int, int, MethodSettings& out) {
  const ScreenDoorKeys& k = keys.screen_door;
  const auto masks = parse_screen_door_masks(k.screen_door_generation);
  if (!masks)
    return KeyProblem{"screen_door_generation",
                      "unknown mask generation '" + k.screen_door_generation + "' (tabular, pixel-tree, white-noise)"};
  out.screen_door = {k.screen_door_mask, *masks};
  if (const auto problem = check(out.screen_door)) return KeyProblem{"screen_door_mask", *problem};
  return std::nullopt;
}

// At each mask side: dt-seed's picture by sub-pixel masks, so its error columns are against
// `reference` as for the dt rows (the accuracy-versus-time table).
std::vector<BenchRow> screen_door_bench_rows(const MethodSettings& base) {
  std::vector<BenchRow> rows;
  for (int side : {8, 16, 32}) {
    rows.push_back({"screen-door " + std::to_string(side) + "x" + std::to_string(side), base});
    rows.back().settings.screen_door.mask_side = side;
  }
  return rows;
}

}  // namespace

extern const KeyGroup k_keys_screen_door{Group::screen_door, "screen_door", kScreenDoorKeys, parse_screen_door,
                                         hash_screen_door, screen_door_to_frame};

extern const Technique k_method_screen_door{
    .id = Method::screen_door,
    .name = "screen-door",
    .summary = "dt-seed's picture by Poon's (2000) sub-pixel screen-door transparency: each surface's alpha picks an "
               "n-pixel mask, z-buffered on an enlarged buffer, box-filtered",
    .groups = bit(Group::dt) | bit(Group::culling) | bit(Group::guard) | bit(Group::screen_door),
    .target_masks = true,
    .searchlight = true,
    .bench_rows = screen_door_bench_rows,
    .bench_default = false,  // its rows: three mask sides
    .bench_slow = true,
};

}  // namespace dtlab::technique
