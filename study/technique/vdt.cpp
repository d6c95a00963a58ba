// The vdt method (Diepstraten, Weiskopf & Ertl 2002) in the registry: the
// paper's falling-off term k and the fixed weights of opaque objects and of
// the background. Guarantees: the vdt keys' ranges are written here only.
#include <array>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

namespace {

using Kind = KeySpec::Kind;
constexpr std::array kVdtKeys{
    KeySpec{"falloff", Kind::number, 0, 1, {}, "--vdt-falloff", "vdt: k of alpha = 1 - (d_min / d_max)^k (default 0.5)"},
    KeySpec{"opaque_alpha", Kind::number, 0, 1, {}, "--vdt-opaque-alpha",
            "vdt: weight of an opaque object seen through a transparent one (default 0.5)"},
    KeySpec{"background_alpha", Kind::number, 0, 1, {}, "--vdt-background-alpha",
            "vdt: weight of the background seen through a transparent object (default 0.5)"},
};

void parse_vdt(KeyReader& r, const Technique& method, Keys& keys) {
  if (auto v = r.number(kVdtKeys[0])) keys.vdt.falloff = *v;
  if (auto v = r.number(kVdtKeys[1])) keys.vdt.opaque_alpha = *v;
  if (auto v = r.number(kVdtKeys[2])) keys.vdt.background_alpha = *v;
  warn_unread(r, method, group(Group::vdt), "a vdt key");
}

void hash_vdt(HashSink& c, const Technique& method, const Keys& keys) {
  if (!method.reads(Group::vdt)) return;  // only then: every other protocol's hash stays as it was
  c.num("falloff", keys.vdt.falloff);
  c.num("opaque_alpha", keys.vdt.opaque_alpha);
  c.num("background_alpha", keys.vdt.background_alpha);
}

// The protocol checked the ranges; check() says again which member is wrong, should a caller
// build the keys by hand.
std::optional<KeyProblem> vdt_to_frame(const Technique&, const Keys& keys, int, int, MethodSettings& out) {
  out.vdt.falloff = static_cast<float>(keys.vdt.falloff);
  out.vdt.opaque_alpha = static_cast<float>(keys.vdt.opaque_alpha);
  out.vdt.background_alpha = static_cast<float>(keys.vdt.background_alpha);
  if (const auto problem = check(out.vdt)) return KeyProblem{problem->substr(0, problem->find(' ')), *problem};
  return std::nullopt;
}

}  // namespace

extern const KeyGroup k_keys_vdt{Group::vdt, "vdt", kVdtKeys, parse_vdt, hash_vdt, vdt_to_frame};

extern const Technique k_method_vdt{
    .id = Method::vdt,
    .name = "vdt",
    .summary = "Diepstraten, Weiskopf & Ertl's view-dependent transparency (distractors transparent, targets and "
               "impenetrable surfaces opaque; image-space depth peeling of two layers)",
    .groups = bit(Group::culling) | bit(Group::vdt),
    .cullable = false,  // every wall is see-through: no wall hides anything by itself
};

}  // namespace dtlab::technique
