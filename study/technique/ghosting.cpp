// The ghosting method in the registry: every distractor in front of a target
// in view is drawn as a ghost, at a fixed weight over what it hides, with its
// edges (silhouettes and creases) drawn as opaque lines (docs/render.md, "ghosting"). Its keys: alpha
// (the ghosts' weight) and edges. Guarantees: the ghosting keys' ranges and
// their conversion are written here only. Never: GL (the passes are
// render/detail/method_ghosting.cpp).
#include <array>
#include <sstream>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

std::optional<std::string> check(const GhostingSettings& s) {
  if (s.alpha >= 0.0f && s.alpha < 1.0f) return std::nullopt;
  std::ostringstream o;
  o << "alpha must be at least 0 and below 1 (got " << s.alpha << ")";
  return o.str();
}

namespace {

using Kind = KeySpec::Kind;
constexpr std::array kGhostingKeys{
    KeySpec{"alpha", Kind::number, 0, 0.99, {}, "--ghosting-alpha", "ghosting: weight of a ghost's surface (default 0.25)"},
    KeySpec{"edges", Kind::boolean, 0, 0, {}, "--ghosting-edges",
            "ghosting: draw the ghosts' edges (silhouettes, creases) as opaque lines (default true)"},
};

void parse_ghosting(KeyReader& r, const Technique& method, Keys& keys) {
  if (auto v = r.number(kGhostingKeys[0])) keys.ghosting.alpha = static_cast<float>(*v);
  if (auto v = r.boolean(kGhostingKeys[1])) keys.ghosting.edges = *v;
  warn_unread(r, method, group(Group::ghosting), "a ghosting key");
}

void hash_ghosting(HashSink& c, const Technique& method, const Keys& keys) {
  if (!method.reads(Group::ghosting)) return;  // only then: every other protocol's hash stays as it was
  c.num("alpha", keys.ghosting.alpha);
  c.str("edges", keys.ghosting.edges ? "true" : "false");
}

std::optional<KeyProblem> ghosting_to_frame(const Technique&, const Keys& keys, int, int, MethodSettings& out) {
  out.ghosting = keys.ghosting;
  if (const auto problem = check(out.ghosting)) return KeyProblem{"alpha", *problem};
  return std::nullopt;
}

}  // namespace

extern const KeyGroup k_keys_ghosting{Group::ghosting, "ghosting", kGhostingKeys, parse_ghosting, hash_ghosting,
                                      ghosting_to_frame};

extern const Technique k_method_ghosting{
    .id = Method::ghosting,
    .name = "ghosting",
    .summary = "the distractors in front of a target drawn as ghosts: at a fixed weight over what they hide, their "
               "edges as opaque lines",
    .groups = bit(Group::culling) | bit(Group::ghosting),
};

}  // namespace dtlab::technique
