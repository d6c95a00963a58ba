// The registry of rendering methods ("techniques"): one registration per
// method names its protocol keys (by key group: typed settings parsed and
// range-checked by the group's own code), its command-line options, its bench
// rows and what the other stages need to know about it. The protocol parser,
// the design hash, the session mapping, `dtlab render`, `dtlab bench`, replay
// and the simulated participant read this table; the renderer's passes are
// registered beside it (study/render/detail/method.h). docs/render.md, "Adding
// a method", says how to add one. Guarantees: GL-free; every name a user can
// write comes from here. Never: a list of method names anywhere else.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "study/technique/settings.h"

namespace dtlab::technique {

// The key groups of settings.h, as bits of Technique::groups.
enum class Group : unsigned {
#define DTLAB_TECHNIQUE_GROUP_ENUM(member, Type) member,
  DTLAB_TECHNIQUE_KEY_GROUPS(DTLAB_TECHNIQUE_GROUP_ENUM)
#undef DTLAB_TECHNIQUE_GROUP_ENUM
};
constexpr unsigned bit(Group g) { return 1u << static_cast<unsigned>(g); }

// A protocol key: name, kind, range (closed; integers and numbers) or choices. The protocol's
// range table (protocol/limits.h) and docs/protocol.md list the keys from here. `cli`: the
// `dtlab render` option that sets it ("" for none).
struct KeySpec {
  enum class Kind { number, integer, choice, boolean };
  std::string_view name;
  Kind kind = Kind::number;
  double min = 0.0, max = 0.0;
  std::span<const std::string_view> choices = {};
  std::string_view cli = {};
  std::string_view help = {};
};

// How a key group reads a [rendering.*] table: the protocol's reader implements it (file, line and
// field in every diagnostic). A getter returns nullopt when the key is absent (an error if
// required) or wrong (diagnosed); every getter marks the key known.
class KeyReader {
 public:
  virtual ~KeyReader() = default;
  virtual std::optional<double> number(const KeySpec& k, bool required = false) = 0;
  virtual std::optional<std::int64_t> integer(const KeySpec& k, bool required = false) = 0;
  virtual std::optional<std::string> choice(const KeySpec& k, bool required = false) = 0;
  virtual std::optional<bool> boolean(const KeySpec& k) = 0;
  virtual bool has(std::string_view key) = 0;  // written in the table
  virtual void error(std::string_view key, std::string message) = 0;
  virtual void warning(std::string_view key, std::string message) = 0;
};

// Where a key group writes its part of the design hash (protocol/design_hash.cpp's canonical
// text); `name` is the key without "rendering.".
class HashSink {
 public:
  virtual ~HashSink() = default;
  virtual void str(std::string_view name, std::string_view value) = 0;
  virtual void num(std::string_view name, double value) = 0;
  virtual void integer(std::string_view name, std::int64_t value) = 0;
};

// A key the frame settings cannot take, named as the author wrote it.
struct KeyProblem {
  std::string key;      // e.g. "aT", "radius"
  std::string message;  // what was expected
};

struct Technique;

// A group of protocol keys, read by every method whose Technique::groups has its bit.
struct KeyGroup {
  Group id;
  std::string_view name;         // the Keys member: "dt", "lens", ...
  std::span<const KeySpec> keys;
  // Reads every key of the group into `keys` (whatever the method), then warns about the keys
  // `method` does not read and checks what depends on it (e.g. a lens's mode).
  void (*parse)(KeyReader& r, const Technique& method, Keys& keys);
  // Writes the group's part of the design hash (its policy: which keys, when).
  void (*hash)(HashSink& sink, const Technique& method, const Keys& keys);
  // Sets the frame settings `method` draws with on a width x height view (both >= 1); nullopt
  // when fine, else the key that cannot be taken. nullptr: the group sets none.
  std::optional<KeyProblem> (*to_frame)(const Technique& method, const Keys& keys, int width, int height,
                                        MethodSettings& out);
};

// A configuration `dtlab bench` times: a label ("dt-seed R=64") and the settings that differ from
// the method's protocol defaults.
struct BenchRow {
  std::string label;
  MethodSettings settings;
};

struct Technique {
  Method id;
  std::string_view name;      // as a protocol and the command line write it: "dt-seed"
  std::string_view summary;   // one line: what it draws, after whom
  unsigned groups = 0;        // bits of the key groups it reads
  bool target_masks = false;  // dynamic transparency: per-target masks, a target query (uses_transparency)
  bool searchlight = false;   // mode = "active" cuts it to a searchlight circle
  bool cullable = true;       // occlusion culling can drop objects under it (vdt: every wall is see-through)
  // A faster version of that method's picture (dt-fast of dt-seed): `dtlab bench` compares the two.
  std::optional<Method> approximates = std::nullopt;
  // `dtlab bench`'s rows beyond the method at its defaults (`base`: the protocol's defaults at the
  // bench's size); nullptr: none.
  std::vector<BenchRow> (*bench_rows)(const MethodSettings& base) = nullptr;
  bool bench_default = true;  // `dtlab bench` times the method at its defaults (reference: the yardstick, no)
  bool bench_slow = false;    // seconds a frame: its rows only on request (`dtlab bench --slow`), one timed frame
  // Mask texel writes of one frame with `targets` targets in view (session/runnable.h bounds it);
  // nullptr: the method's work does not grow per target that way.
  double (*mask_texels)(const Keys& keys, long long targets) = nullptr;

  bool reads(Group g) const { return (groups & bit(g)) != 0; }
};

// Every method, in Method order.
std::span<const Technique* const> all();
// Every key group, in the design hash's order.
std::span<const KeyGroup* const> key_groups();
const Technique& of(Method m);
const Technique* find(std::string_view name);  // nullptr if no method has this name
std::string_view to_string(Method m);          // of(m).name
std::optional<Method> parse_method(std::string_view s);
bool uses_transparency(Method m);  // of(m).target_masks
// "standard, dt-seed, ..." (for messages and --help).
std::string names(std::string_view separator = ", ");

// The protocol's keys of `method` in frame settings for a width x height view (both >= 1): every
// group the method reads, in order. nullopt when fine.
std::optional<KeyProblem> frame_settings(const Technique& method, const Keys& keys, int width, int height,
                                         MethodSettings& out);
// "has no effect with method = \"standard\" (a lens key)" for each key of `group` written in the
// table: the warning every group gives for keys its method does not read (`except`: keys the group
// diagnoses itself).
void warn_unread(KeyReader& r, const Technique& method, const KeyGroup& group, std::string_view reason,
                 std::span<const std::string_view> except = {});
const KeyGroup& group(Group g);
// Points the aid a participant moves at `pointer` (output pixels, origin top-left): an active
// searchlight, a lens that follows the cursor. A session's view and replay both aim through here,
// so that a replayed frame is the frame the participant saw.
void aim(MethodSettings& s, glm::vec2 pointer);

}  // namespace dtlab::technique
