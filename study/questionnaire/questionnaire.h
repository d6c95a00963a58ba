// Questionnaire items as plain data, and the item-type seam. Every item type
// (rating, likert, slider, choice, multiple-choice, numeric, text, depth-test)
// is ONE registration, an ItemType in its own file under items/, listed once
// in item_types.def: the keys it takes, its checks against the design, how it
// expands into questions, how an answer is checked and stored, how a
// simulated participant answers it, and how its stored values are exported
// and summarised. The window draws each type with the screen of the same name
// in app/run/items/ (the same .def list). docs/questionnaires.md says how to
// add a type. Guarantees: pure functions of their inputs. Never: reads TOML,
// writes SQL, draws, or keeps state between calls.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "study/common/error.h"
#include "study/common/random.h"

namespace dtlab::questionnaire {

// --- keys: what a type reads from its [questionnaire.<id>] table -----------------------------------

struct NumberPair {  // [min, max]
  double min = 0, max = 0;
  bool operator==(const NumberPair&) const = default;
};
using KeyValue = std::variant<std::monostate, bool, std::int64_t, double, std::string, std::vector<std::string>, NumberPair>;

enum class KeyKind {
  text,          // a non-empty string
  choice,        // one of `allowed`
  boolean,       // true or false
  integer,       // an integer in [min, max]
  number,        // a number in [min, max]
  strings,       // an array of min..max unique non-empty strings
  int_range,     // [a, b], integers, each in [min, max], a <= b (a < b if increasing)
  number_range,  // [a, b], numbers, each in [min, max], a <= b (a < b if increasing)
};

// One key of an item type (or an instrument), declared once: the protocol reader checks it,
// validate's range table and docs/protocol.md list it, the design hash includes it unless wording.
struct KeySpec {
  std::string name;
  KeyKind kind = KeyKind::text;
  bool required = false;
  double min = 0, max = 0;            // integer, number: the value; strings: how many; ranges: each end
  bool increasing = false;            // ranges: a < b
  std::vector<std::string> allowed;   // choice: the values
  KeyValue fallback;                  // the value when the key is absent (monostate: none)
  bool wording = false;               // text only shown to people: never part of the design hash

  // Declaration in one expression: KeySpec::of("scale", KeyKind::int_range).within(-100, 100).or_else(...).
  static KeySpec of(std::string name, KeyKind kind) {
    KeySpec k;
    k.name = std::move(name);
    k.kind = kind;
    return k;
  }
  KeySpec& needed() { required = true; return *this; }
  KeySpec& within(double lo, double hi) { min = lo; max = hi; return *this; }
  KeySpec& strictly() { increasing = true; return *this; }
  KeySpec& among(std::vector<std::string> values) { allowed = std::move(values); return *this; }
  KeySpec& or_else(KeyValue v) { fallback = std::move(v); return *this; }
  KeySpec& shown_only() { wording = true; return *this; }
};

using Keys = std::map<std::string, KeyValue, std::less<>>;

// --- items ----------------------------------------------------------------------------------------

// When an item is asked: `when = "end" | "block" | "task" | "level:<factor>"`.
struct When {
  enum class Kind { end, block, task, level };
  Kind kind = Kind::end;
  std::string factor;  // level: after the last block of each level of this factor
  bool operator==(const When&) const = default;
};
std::string to_string(const When& w);              // "end", "block", "task", "level:technique"
std::optional<When> parse_when(std::string_view text);  // the inverse; nullopt when malformed

struct ItemType;
struct Instrument;

// One question source of the protocol: a [questionnaire.<id>] table with a type, or one item of an
// instrument's block (id "<block>.<sub>", e.g. "tlx.mental").
struct Item {
  std::string id;
  const ItemType* type = nullptr;    // registry entry (program lifetime)
  std::string prompt;
  When when;
  Keys keys;                         // the type's keys (defaults filled; resolved by its check)
  std::set<std::string, std::less<>> written;  // the keys the file sets
  const Instrument* instrument = nullptr;      // the instrument it belongs to, or nullptr
  std::string block;                 // the instrument's table id ("" for a plain item)
  std::string sub;                   // its id inside the instrument ("mental", "w.mental-physical")

  // The value of one of its type's keys (the fallback when a hand-built item lacks it);
  // std::invalid_argument for a key its type does not declare or of another kind.
  const KeyValue& value(std::string_view key) const;
  std::int64_t integer(std::string_view key) const;
  double number(std::string_view key) const;
  bool boolean(std::string_view key) const;
  const std::string& text(std::string_view key) const;
  const std::vector<std::string>& strings(std::string_view key) const;
  NumberPair range(std::string_view key) const;
};

// The names an item's checks and expansion need from the protocol's design.
struct DesignNames {
  struct Factor {
    std::string name;
    std::vector<std::string> levels;
  };
  std::vector<Factor> factors;      // protocol order
  std::vector<std::string> scenarios, renderings;
  std::string rendering_factor;     // the factor with role = "rendering" ("" if none)
  const Factor* factor(std::string_view name) const;  // nullptr if none
};

// Where a type reports what is wrong with an item (the protocol reader puts it at the key's line).
class Problems {
 public:
  virtual ~Problems() = default;
  virtual void error(std::string_view key, const std::string& message) = 0;  // key "" = the item's table
  virtual void error_at(std::string_view key, std::size_t index, const std::string& message) = 0;  // an array entry
  virtual void warning(std::string_view key, const std::string& message) = 0;
};

// --- occasions and questions -----------------------------------------------------------------------

// One point of a participant's plan (design::PlannedTrial without what questionnaires ignore).
struct PlanPoint {
  int position = 0, block = 0;
  std::string task;
  std::vector<std::pair<std::string, std::string>> levels;  // factor -> level, protocol order
};

// One time a questionnaire is asked: after a block, a task set, the last block of a level, or the end.
struct Occasion {
  When::Kind kind = When::Kind::end;
  std::string factor;    // level occasions: the factor
  std::string scope;     // "" (end) | "block=2" | "block=2;task=T1" | "technique=lens"
  int block = 0;         // block and task occasions
  std::string task;      // task occasions
  std::vector<std::pair<std::string, std::string>> levels;  // the condition it follows (end: none;
                                                            // level: that factor's level alone)
  int after_position = 0;  // the plan position it comes after
};

// The occasions of a plan at which some item is asked, in the order they come: after each
// position, its task set's, then its block's, then each factor's level (factor order) occasion,
// and the end after the last position. `factors` names the protocol's factors in order.
std::vector<Occasion> occasions(std::span<const Item> items, std::span<const PlanPoint> plan,
                                const std::vector<std::string>& factors);
// Whether `item` is asked at `o` (its `when` is the occasion's kind and factor).
bool asked_at(const Item& item, const Occasion& o);

// One question, expanded from an item; stored as one row (item id, occasion scope;own scope, value).
struct Question {
  const Item* item = nullptr;
  std::string scope;  // its own: "" | "scenario=abstract;transparency=on" (rating per factors) | "pair=2"
  std::vector<std::pair<std::string, std::string>> levels;  // rating per factors: the levels it is about
  std::vector<std::string> options;  // choice, multiple choice: what may be answered (stored values)
  int pair = 0;                      // depth test: 1-based pair number
  std::uint32_t object_a = 0, object_b = 0;  // depth test: Object::id of the two objects shown
};
// The questions of `item` in order (its type's expansion).
std::vector<Question> expand(const Item& item, const DesignNames& design);
// The scope a question is stored under at occasion `o`: the occasion's scope, then the question's, joined by ';'.
std::string stored_scope(const Occasion& o, const Question& q);
// The inverse for a stored row of `item`: {occasion scope, own scope}.
std::pair<std::string, std::string> split_scope(const Item& item, const std::string& stored);

// An answer as a responder gives it: a number (rating, Likert, slider, numeric; depth test: the
// Object::id judged closer), a text (choice, free text), or several texts (multiple choice).
using Answer = std::variant<double, std::string, std::vector<std::string>>;
// As the store keeps it (questionnaire_answers.value_number | value_text).
using StoredValue = std::variant<double, std::string>;

// What encode needs beyond the question: the depth test's key.
struct EncodeContext {
  std::function<std::optional<std::uint32_t>(const Question&)> closer;  // Object::id of the pair's closer object
};
// The stored form of `a`; an Error (field "questionnaire.<id>[scope]") when it does not fit `q`.
Result<StoredValue> encode(const Question& q, const Answer& a, const EncodeContext& ctx = {});

// --- simulated participants -------------------------------------------------------------------------

// A recorded trial as a simulated participant remembers it.
struct PastTrial {
  int position = 0, block = 0;
  std::string task;
  std::vector<std::pair<std::string, std::string>> levels;
  double completion_s = 0;
  bool answered = false;
  bool practice = false;
};

// What a simulated participant brings to one occasion (study/sim fills it; docs/sim.md).
struct Experience {
  const DesignNames* design = nullptr;
  const Occasion* occasion = nullptr;
  std::vector<PastTrial> history;  // every trial recorded so far, position order
  std::uint64_t seed = 0;          // the participant's: instruments draw their latent traits from it
  double rating_bias = 0;          // added to every rating, in quarters of its scale
  double rating_gain = 1.5;        // rating = middle + gain x log2(reference time / condition time)
  double rating_noise = 0.5;       // sd of a rating's noise, in quarters of its scale
  std::optional<double> depth_confidence;  // 0..1: how sure this occasion's depth judgements felt
  std::function<std::optional<std::uint32_t>(const Question&)> depth_choice;  // the Object::id judged closer
  std::vector<std::pair<const Question*, Answer>> given;  // answered earlier at this occasion, in order
  Stream* rng = nullptr;           // this occasion's stream
};
// A simulated participant's answer to `q` (its instrument's model, else its type's).
Answer simulate(const Question& q, Experience& e);

// --- the item-type registry ----------------------------------------------------------------------

// How reports and exports treat a type's stored values.
enum class Measure {
  ordinal,   // points on a scale (rating, Likert): rank tests
  interval,  // numbers (slider, numeric): means, RM-ANOVA
  nominal,   // one option (choice): counts
  multiple,  // several options (multiple choice): counts per option
  text,      // free text: listed
  correct,   // 1 right, 0 wrong (depth test): sums
};
std::string_view to_string(Measure m);

// One item type. Function pointers may be null where noted.
struct ItemType {
  std::string name;     // as `type = "..."` writes it
  std::string summary;  // one line: what the participant does
  std::vector<KeySpec> keys;  // besides type, prompt, when
  Measure measure = Measure::ordinal;
  // Checks between keys and against the design; may resolve keys (a choice's factor becomes its
  // options). Null: nothing to check.
  void (*check)(Item& item, const DesignNames& design, Problems& problems) = nullptr;
  // The item's questions in order (one by default: null).
  std::vector<Question> (*expand)(const Item& item, const DesignNames& design) = nullptr;
  // The stored value of an answer, or an Error saying what was expected.
  Result<StoredValue> (*encode)(const Question& q, const Answer& a, const EncodeContext& ctx) = nullptr;
  // A simulated participant's answer (docs/sim.md, "Questionnaire").
  Answer (*simulate)(const Question& q, Experience& e) = nullptr;
  // The scale's ends (ordinal, interval, correct), for reports; null: none.
  NumberPair (*bounds)(const Item& item) = nullptr;
  // A stored value as the export's `label` column writes it (a Likert point's label); null: "".
  std::string (*label)(const Item& item, const StoredValue& v) = nullptr;
};

// Every registered type, in item_types.def order.
std::span<const ItemType* const> item_types();
const ItemType* find_item_type(std::string_view name);  // nullptr if none
// A stored value's label (the type's `label`, or "").
std::string value_label(const Item& item, const StoredValue& v);

// The field an item's errors name: "questionnaire.<id>" and "[scope]" when the scope is not empty.
std::string field_of(const Question& q);

}  // namespace dtlab::questionnaire
