// Internal: what the item types and instruments share: their registration
// functions (declared from item_types.def), message helpers, and what a
// simulated participant reads from its experience (times per condition, how
// hard the occasion's condition felt). Never: state between calls.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "study/questionnaire/instrument.h"
#include "study/questionnaire/questionnaire.h"

namespace dtlab::questionnaire {

#define DTLAB_ITEM_TYPE(id) const ItemType& item_type_##id();
#include "study/questionnaire/item_types.def"
#undef DTLAB_ITEM_TYPE

const Instrument& instrument_nasa_tlx();
const Instrument& instrument_sus();
const Instrument& instrument_ssq();

namespace detail {

std::string quoted_list(const std::vector<std::string>& items);  // "\"a\", \"b\""
std::string num(double v);                                        // shortest form that reads back
// An Error about the answer to q (field "questionnaire.<id>[scope]", kind invalid_input).
Error answer_error(const Question& q, const std::string& message);
// A number answer, or an Error naming what was expected.
Result<double> number_answer(const Question& q, const Answer& a, const std::string& expected);

using Levels = std::vector<std::pair<std::string, std::string>>;

// Mean completion time and share of unanswered trials of the recorded, unpracticed trials matching
// `levels` (every factor but `except`).
struct CellTimes {
  double mean = 0;
  double unanswered = 0;
  int n = 0;
};
CellTimes cell_times(const std::vector<PastTrial>& history, const Levels& levels, const std::string& except);

// The condition a question is about: its own levels (a rating per factors), else its occasion's.
Levels condition_of(const Question& q, const Experience& e);
// The factor a condition is compared across: the rendering factor when the levels hold it, else the
// occasion's factor, else the levels' first factor ("" without levels).
std::string compared_factor(const Levels& levels, const Experience& e);

// How the participant fared in `levels` against the same other levels under every level of the
// compared factor: strain = log2(condition's mean time / reference mean time) (> 0: slower than
// its own average so far), and the share of trials left unanswered there. nullopt without trials.
struct Strain {
  double strain = 0;
  double unanswered = 0;
};
std::optional<Strain> strain_of(const Levels& levels, const Experience& e);

// A point on [lo, hi] from how easy the condition felt (the reference study's rating model,
// docs/sim.md): middle + unit x (gain x -strain - 2 x unanswered + bias + noise), rounded to
// `step` from lo and clamped; unit = (hi - lo) / 4. Without a condition: the middle plus bias and noise.
double ease_point(double lo, double hi, double step, const Question& q, Experience& e);

}  // namespace detail
}  // namespace dtlab::questionnaire
