// The registry's tables (see technique.h), generated from settings.h's lists:
// each method and key group is defined in the file that implements it.
#include <algorithm>
#include <array>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {

#define DTLAB_TECHNIQUE_DECLARE_METHOD(id) extern const Technique k_method_##id;
DTLAB_TECHNIQUE_METHODS(DTLAB_TECHNIQUE_DECLARE_METHOD)
#undef DTLAB_TECHNIQUE_DECLARE_METHOD
#define DTLAB_TECHNIQUE_DECLARE_GROUP(member, Type) extern const KeyGroup k_keys_##member;
DTLAB_TECHNIQUE_KEY_GROUPS(DTLAB_TECHNIQUE_DECLARE_GROUP)
#undef DTLAB_TECHNIQUE_DECLARE_GROUP

namespace {
#define DTLAB_TECHNIQUE_METHOD_ADDRESS(id) &k_method_##id,
constexpr std::array kMethods{DTLAB_TECHNIQUE_METHODS(DTLAB_TECHNIQUE_METHOD_ADDRESS)};
#undef DTLAB_TECHNIQUE_METHOD_ADDRESS
#define DTLAB_TECHNIQUE_GROUP_ADDRESS(member, Type) &k_keys_##member,
constexpr std::array kGroups{DTLAB_TECHNIQUE_KEY_GROUPS(DTLAB_TECHNIQUE_GROUP_ADDRESS)};
#undef DTLAB_TECHNIQUE_GROUP_ADDRESS
}  // namespace

std::span<const Technique* const> all() { return kMethods; }
std::span<const KeyGroup* const> key_groups() { return kGroups; }
const Technique& of(Method m) { return *kMethods[static_cast<std::size_t>(m)]; }
const KeyGroup& group(Group g) { return *kGroups[static_cast<std::size_t>(g)]; }

const Technique* find(std::string_view name) {
  for (const Technique* t : kMethods)
    if (t->name == name) return t;
  return nullptr;
}

std::string_view to_string(Method m) { return of(m).name; }

std::optional<Method> parse_method(std::string_view s) {
  if (const Technique* t = find(s)) return t->id;
  return std::nullopt;
}

bool uses_transparency(Method m) { return of(m).target_masks; }

std::string names(std::string_view separator) {
  std::string out;
  for (const Technique* t : kMethods) {
    if (!out.empty()) out += separator;
    out += t->name;
  }
  return out;
}

std::optional<KeyProblem> frame_settings(const Technique& method, const Keys& keys, int width, int height,
                                         MethodSettings& out) {
  out.method = method.id;
  for (const KeyGroup* g : kGroups)
    if (method.reads(g->id) && g->to_frame != nullptr)
      if (auto problem = g->to_frame(method, keys, width, height, out)) return problem;
  return std::nullopt;
}

void warn_unread(KeyReader& r, const Technique& method, const KeyGroup& group, std::string_view reason,
                 std::span<const std::string_view> except) {
  if (method.reads(group.id)) return;
  for (const KeySpec& k : group.keys)
    if (std::find(except.begin(), except.end(), k.name) == except.end() && r.has(k.name))
      r.warning(k.name, "has no effect with method = \"" + std::string(method.name) + "\" (" + std::string(reason) + ")");
}

void aim(MethodSettings& s, glm::vec2 pointer) {
  if (s.dt.mode == DtMode::active) s.dt.searchlight_center = pointer;
  if (of(s.method).reads(Group::lens) && s.lens.follows_cursor) s.lens.center = pointer;
}

}  // namespace dtlab::technique
