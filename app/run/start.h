// The experimenter's screens around a participant's session in `dtlab run`:
// the start screen (the protocol's title and design, progress per order row
// from the ledger, enrolling a new participant with the protocol's
// demographics, resuming a running session in one click, releasing an
// abandoned one) and the end screen. Enrollment and release go through the
// store; an ID that finished is refused with a clear message.
#pragma once
#include <optional>
#include <string>

#include "app/run/ui.h"
#include "study/protocol/protocol.h"
#include "study/store/store.h"

namespace dtlab::run {

// Shows the start screen until the experimenter starts (or resumes) a session: returns the
// participant id, enrolled with their demographics; nullopt when they quit. `preset` fills the
// ID field (--participant).
Result<std::optional<std::string>> start_screen(Ui& ui, store::Store& store, const protocol::Protocol& p,
                                                const std::string& preset);

// Shows `title` and `text` until the experimenter clicks Close (or presses Escape).
Status end_screen(Ui& ui, const std::string& screen, const std::string& title, const std::string& text);

}  // namespace dtlab::run
