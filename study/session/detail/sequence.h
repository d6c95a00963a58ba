// The pages of the session's sequence around the trials, built from the
// protocol and the plan (docs/session.md, "The sequence"): consent,
// information pages, a block's break and announcement, the instructions of
// the factor levels a block meets first, breaks inside a block, and the
// feedback after a practice trial. Pure functions of (protocol, plan,
// position): a resumed session shows the pages an uninterrupted one would at
// the same place. Never: shows, stores or times anything (the runner does).
#pragma once
#include <optional>
#include <vector>

#include "study/design/plan.h"
#include "study/protocol/protocol.h"
#include "study/scene/scene.h"
#include "study/session/session.h"
#include "study/store/score.h"

namespace dtlab::session::detail {

// The [consent] page; the protocol must have one. `shown` is the SHA-256 of the text.
PageSpec consent_page(const protocol::Protocol& p);

// The [pages.*] of one place, in file order.
std::vector<PageSpec> information_pages(const protocol::Protocol& p, protocol::Page::When when);

// The pages before the first trial of `block` when the session reaches it by running: the break
// after the previous block (block > 1 and breaks.after_blocks), the block's announcement
// (announce_blocks), and the instructions of every factor level whose first block in `plan` this is.
std::vector<PageSpec> block_pages(const protocol::Protocol& p, const design::Plan& plan, int block);

// A break inside a block (breaks.every_trials) after trial `last`, when `next` is in the same block
// and `last` is a multiple of every_trials trials into it; nullopt otherwise.
std::optional<PageSpec> trial_break(const protocol::Protocol& p, const design::Plan& plan,
                                    const design::PlannedTrial& last, const design::PlannedTrial& next);

// The feedback after practice trial `t`: the correct answer beside the participant's.
PageSpec feedback_page(const protocol::Protocol& p, const design::PlannedTrial& t, const store::Answer& truth,
                       const std::optional<store::Answer>& given);

// What participants read for a planned trial's block: its factors' level labels, e.g.
// "X-ray view, Abstract scenes".
std::string block_levels_text(const protocol::Protocol& p, const design::PlannedTrial& t);

}  // namespace dtlab::session::detail
