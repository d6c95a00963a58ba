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

// Who the start screen chose: the participant, and the demographics entered for a new one.
struct StartChoice {
  std::string participant;
  store::Demographics demographics;  // a new participant's; enrolled already unless the protocol asks consent
};

// Shows the start screen until the experimenter starts (or resumes) a session: returns who was
// chosen, nullopt when they quit. A new participant is enrolled with their demographics, except
// where the protocol has a consent page: then nothing is stored until they answer it (the
// session does that, session::run_session). `preset` fills the ID field (--participant).
Result<std::optional<StartChoice>> start_screen(Ui& ui, store::Store& store, const protocol::Protocol& p,
                                                const std::string& preset);

// Shows `title` and `text` until the experimenter clicks `close` (or presses Escape).
Status end_screen(Ui& ui, const std::string& screen, const std::string& title, const std::string& text,
                  const std::string& close);

}  // namespace dtlab::run
