// Standard instruments as ready protocol blocks (`instrument = "nasa-tlx" |
// "sus" | "ssq"` instead of `type`): each expands into items of the plain
// types with their published wording, and scores a participant's answers at
// one occasion with its published scoring (NASA-TLX: Hart & Staveland 1988,
// Hart 2006; SUS: Brooke 1996; SSQ: Kennedy, Lane, Berbaum & Lilienthal 1993).
// Scores are never stored: the export and the report compute them from the
// raw answers. Guarantees: a score is computed only from a complete set of
// answers (nullopt otherwise). Never: reads files or the store.
#pragma once
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "study/questionnaire/questionnaire.h"

namespace dtlab::questionnaire {

// One score an instrument computes.
struct Scale {
  std::string id;     // "raw", "weighted", "score", "nausea", ...
  std::string label;  // "Raw TLX", "SUS score", ...
  double min = 0, max = 0;
};

// Answers of one participant at one occasion, by sub-item id ("mental", "w.mental-physical", "q3").
using SubAnswers = std::map<std::string, StoredValue, std::less<>>;

struct Instrument {
  std::string name;      // as `instrument = "..."` writes it
  std::string title;     // "NASA Task Load Index (NASA-TLX)"
  std::string citation;  // the publication its items and scoring follow
  std::vector<KeySpec> keys;  // its own keys besides instrument and when
  // Its items (sub, type, prompt, keys), in the order they are asked; ids are filled by the parser.
  std::vector<Item> (*items)(const Keys& keys) = nullptr;
  std::vector<Scale> (*scales)(const Keys& keys) = nullptr;
  // One value per scale (scales' order); nullopt where an answer it needs is missing or malformed.
  std::vector<std::optional<double>> (*score)(const Keys& keys, const SubAnswers& answers) = nullptr;
  // A simulated participant's answer to one of its items (docs/sim.md, "Instruments").
  Answer (*simulate)(const Item& item, const Question& q, Experience& e) = nullptr;
};

// One instrument block of a protocol: [questionnaire.<id>] with `instrument = ...`.
struct InstrumentUse {
  std::string id;
  const Instrument* instrument = nullptr;
  When when;
  Keys keys;
  std::vector<std::string> items;  // its items' ids ("<id>.<sub>"), in order
};

std::span<const Instrument* const> instruments();
const Instrument* find_instrument(std::string_view name);  // nullptr if none

// The instrument's items for block `use`, ids "<use.id>.<sub>", `when` and `instrument` set.
std::vector<Item> instrument_items(const InstrumentUse& use);

}  // namespace dtlab::questionnaire
