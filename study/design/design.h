// From a protocol to participants' trial plans: the order rows of its
// counterbalancing scheme and the ordered trial list of one participant.
// Guarantees: make_plan is a pure function of (protocol, enrollment index,
// order row): the same plan on every machine, independent of what ran before.
// Enrollment index k gets order row k mod order_rows(p) unless the caller
// (the store's participant ledger) assigns another row. Seeds: seeds.h.
#pragma once
#include <optional>

#include "study/design/latin.h"
#include "study/design/plan.h"
#include "study/protocol/protocol.h"

namespace dtlab::design {

// Number of rows of the protocol's ordering (for unit = blocks: outer x nested); at most
// protocol::limits::kOrderRows.max for a loaded protocol (more: std::invalid_argument).
int order_rows(const protocol::Protocol& p);

// One row of the ordering: condition indices (into p.conditions) in session
// order. 0 <= row < order_rows(p), else std::invalid_argument.
Order order_row(const protocol::Protocol& p, int row);

// Every row of the ordering; order_table(p)[r] == order_row(p, r).
OrderTable order_table(const protocol::Protocol& p);

// Participant `index`'s plan (index >= 0). The row defaults to index mod
// order_rows(p). Per block (one condition), the scenario's tasks in file
// order; per task, training.practice_trials practice trials and then the
// task's recorded trials. `p` must come from load_protocol (checked).
Plan make_plan(const protocol::Protocol& p, int index, std::optional<int> order_row = std::nullopt);

}  // namespace dtlab::design
