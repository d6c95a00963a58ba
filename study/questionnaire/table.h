// Questionnaire answers as a tidy table: one row per participant x item x
// occasion x own scope (each stored answer), with the occasion's kind, block,
// task and factor levels (from the participant's plan), then, per participant
// and occasion, one row per scale of every instrument scored from that
// occasion's answers (type "score"). The export (`dtlab export
// --questionnaires`) writes it as CSV; the report reads it. Guarantees: rows
// in participant order, then occasion order (as the session asked them), then
// the protocol's item order; an instrument scale is a row only when its
// answers are complete. Never: reads the store (callers hand the rows in).
#pragma once
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "study/questionnaire/instrument.h"
#include "study/questionnaire/questionnaire.h"

namespace dtlab::questionnaire {

// One stored answer (store::QuestionnaireRecord without the session id).
struct StoredAnswer {
  std::string participant;
  std::string item, scope;  // scope as stored: the occasion's, then the question's own
  StoredValue value;
  std::string answered_at;
};

// A participant's plan, for the levels of the blocks their answers follow.
struct ParticipantPlan {
  std::string participant;
  std::vector<PlanPoint> plan;
};

struct TableRow {
  std::string participant;
  std::string occasion;        // "end", "block", "task", "level:<factor>"; "" for an item the protocol lacks
  std::string occasion_scope;  // "" | "block=2" | "block=2;task=T1" | "technique=lens"
  int block = 0;               // block and task occasions; 0 otherwise
  std::string task;            // task occasions; "" otherwise
  std::vector<std::string> levels;  // per factor of Table::factors: the condition the occasion follows ("" = none)
  std::string item;            // the item id ("tlx.mental"), or "<block>:<scale>" for a score ("tlx:raw")
  std::string instrument;      // "nasa-tlx", "sus", "ssq", or ""
  std::string type;            // the item's type, "score" for a scale, "" for an item the protocol lacks
  std::string scope;           // the question's own scope ("pair=1", "scenario=abstract;transparency=on")
  std::optional<double> number;
  std::optional<std::string> text;
  std::string label;           // a Likert point's or an option's label; a scale's label
  std::string answered_at;     // "" for a score
};

struct Table {
  std::vector<std::string> factors;
  std::vector<TableRow> rows;
};

// The table of `answers` under the protocol's `items` and `instruments`; `factors` names the
// protocol's factors in order; `plans` holds every participant in the order the rows take.
Table answer_table(std::span<const Item> items, std::span<const InstrumentUse> instruments,
                   const std::vector<std::string>& factors, std::span<const ParticipantPlan> plans,
                   std::span<const StoredAnswer> answers);

// Scores of one instrument block for one participant at one occasion, from that occasion's
// answers to its items (by item id, own scope ""); one value per scale, nullopt where incomplete.
std::vector<std::optional<double>> score_occasion(const InstrumentUse& use, const SubAnswers& answers);

}  // namespace dtlab::questionnaire
