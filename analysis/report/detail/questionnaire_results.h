// What the report finds in the questionnaire answers beyond the end-of-session
// items (section_questionnaire.cpp): each instrument's scales (scored by the
// instrument's published scoring from the raw answers) and each item asked
// after a block, a task set or a level, per condition: a participant x
// condition matrix (a participant's mean over the occasions in a condition)
// with its test by the item's measure -- RM-ANOVA for scores and numbers
// (sliders, numeric), Friedman's test across the compared factor's levels
// for points on a scale (ratings, Likert items), as the report treats
// ratings -- counts of the options chosen per condition, and every free-text
// answer with the condition it followed. A plain struct computed from the
// Context's data alone; layout_instruments.cpp lays it out. No I/O.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {

// One measure per condition: an instrument's scale, or an item asked at an occasion.
struct ConditionMeasure {
  std::string id;                   // "tlx:raw" (a scale: "<block>:<scale>"), or the item id
  std::string label;                // "NASA-TLX: Raw TLX (mean of the six subscales)", or the prompt
  std::string instrument;           // "nasa-tlx", ... ("" for an item)
  std::string occasion;             // "block", "task", "level:technique", "end"
  double min = 0, max = 0;          // the scale's ends
  const TestReport* test = nullptr; // per condition; null when asked at the end only (no condition)
  stats::Descriptives overall;      // over participants (each one's mean over its occasions)
};

// The options chosen at an occasion's condition, for a choice or multiple-choice item.
struct ConditionCounts {
  std::string item, prompt, condition;
  std::map<std::string, int> chosen;  // option -> participants x occasions choosing it
  int answers = 0;
};

struct FreeText {
  std::string participant, item, condition;  // condition "" at the end
  std::string text;
};

// A participant's score on an instrument's scale at one occasion (a row of instrument_scores.csv).
struct InstrumentScore {
  std::string participant, instrument, scale, occasion, occasion_scope, condition;
  double value = 0;
};

struct QuestionnaireResults {
  std::vector<ConditionMeasure> measures;  // instruments' scales (protocol order), then items
  std::vector<ConditionCounts> counts;
  std::vector<FreeText> texts;             // non-empty answers, participant order then protocol order
  std::vector<InstrumentScore> scores;     // participant x occasion x scale
  Tally tally;                             // the measures' tests
};

// Computes everything above; tests are stored in ctx (ctx.add_test, section "instruments") and counted in
// the result's tally.
QuestionnaireResults questionnaire_results(Context& ctx);

// The section "Instruments and questions per condition": questionnaire_results(),
// or nullopt (no section) when the protocol has nothing of it.
std::optional<QuestionnaireResults> section_instruments(Context& ctx);

}  // namespace dtlab::report::detail
