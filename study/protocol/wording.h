// Participant-facing wording: every string a participant (or the experimenter,
// on the participant's screen) reads during a session, by key, with its
// English default, overridable by the protocol's [text] table
// (docs/protocol.md, "[text]"). Guarantees: every key the code asks for is in
// the table below (an unknown key is a programmer error, asserted); a
// protocol's [text] may set only these keys and only the {placeholders} each
// key lists; wording never enters the design hash. Never: formats numbers
// for the participant's locale (the caller passes text).
#pragma once
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "study/protocol/protocol.h"

namespace dtlab::protocol {

struct TextKey {
  std::string_view key;           // e.g. "break.title"
  std::string_view english;       // the default, e.g. "Break"
  std::string_view placeholders;  // the {names} it may hold, space separated, e.g. "done blocks"
};

// Every key, in the order docs/protocol.md lists them.
std::span<const TextKey> text_keys();
// The key's entry; nullptr for a key that does not exist.
const TextKey* find_text_key(std::string_view key);

// The protocol's wording for `key` (its [text] entry, else the English default), with each
// {name} replaced by its value. Example: text(p, "break.after_block", {{"done", "1"}, {"blocks", "4"}}).
std::string text(const Protocol& p, std::string_view key,
                 std::initializer_list<std::pair<std::string_view, std::string>> values = {});

// What participants read for level `level` of the factor named `factor`: its label (level_label),
// or the level itself when the protocol has no such factor or level.
std::string level_text(const Protocol& p, std::string_view factor, std::string_view level);

// Every text of the protocol a participant or the experimenter may read in a session, joined:
// the wording table's values (the protocol's and the defaults), the title, level labels and
// instructions, consent and page texts, task instructions, questionnaire prompts and options,
// demographic prompts and options. The window builds its font atlas for these characters.
std::string participant_text(const Protocol& p);

}  // namespace dtlab::protocol
