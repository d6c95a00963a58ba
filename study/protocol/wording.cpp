// The wording table (wording.h): every participant-facing string by key with
// its English default and the placeholders it may hold, and text(), which
// picks the protocol's [text] entry or the default and fills placeholders.
#include "study/protocol/wording.h"

#include <array>
#include <cassert>

namespace dtlab::protocol {
namespace {

// Keep in step with docs/protocol.md, "[text]" (tests/protocol/test_wording.cpp compares them).
constexpr std::array kKeys{
    // Buttons and hints shared by many screens.
    TextKey{"button.continue", "Continue", ""},
    // Consent.
    TextKey{"consent.title", "Consent", ""},
    TextKey{"consent.agree", "I agree", ""},
    TextKey{"consent.decline", "I do not agree", ""},
    TextKey{"consent.declined", "Thank you. You have declined to take part; nothing else is recorded.", ""},
    // Breaks: after a block, or inside one; what comes next; how to go on.
    TextKey{"break.title", "Break", ""},
    TextKey{"break.after_block", "Block {done} of {blocks} is done. Take a short break.", "done blocks"},
    TextKey{"break.inside_block", "Take a short break.", ""},
    TextKey{"break.next", "Next: {next}.", "next"},
    TextKey{"break.go_on", "Press Space or click Continue when you are ready.", ""},
    TextKey{"break.wait", "You can go on in {seconds} s.", "seconds"},
    TextKey{"break.ends_in", "The session goes on by itself in {seconds} s.", "seconds"},
    // A block's announcement and a level's instructions.
    TextKey{"announce.title", "Next block", ""},
    TextKey{"announce.text", "Block {block} of {blocks}. Next: {next}.", "block blocks next"},
    TextKey{"level.title", "Next: {level}", "level"},
    // Practice trials.
    TextKey{"practice.label", "Practice", ""},
    TextKey{"feedback.title", "Practice: the answer", ""},
    TextKey{"feedback.count", "There were {truth}; you answered {given}.", "truth given"},
    TextKey{"feedback.letter", "The letter was {truth}; you chose {given}.", "truth given"},
    TextKey{"feedback.position", "The object was {distance} units from the point you marked.", "distance"},
    TextKey{"feedback.none", "You gave no answer. The answer was {truth}.", "truth"},
    TextKey{"feedback.position_truth", "the marked place on the floor plan", ""},
    // The trial counter.
    TextKey{"trial.counter", "Trial {trial} of {trials}", "trial trials"},
};

}  // namespace

std::span<const TextKey> text_keys() { return kKeys; }

const TextKey* find_text_key(std::string_view key) {
  for (const TextKey& k : kKeys)
    if (k.key == key) return &k;
  return nullptr;
}

std::string text(const Protocol& p, std::string_view key,
                 std::initializer_list<std::pair<std::string_view, std::string>> values) {
  const TextKey* k = find_text_key(key);
  assert(k && "text(): no such wording key; add it to kKeys in study/protocol/wording.cpp and to docs");
  std::string out = k ? std::string(k->english) : std::string(key);
  for (const auto& [name, value] : p.text)
    if (name == key) out = value;
  for (const auto& [name, value] : values) {
    const std::string mark = "{" + std::string(name) + "}";
    for (std::size_t at = out.find(mark); at != std::string::npos; at = out.find(mark, at + value.size()))
      out.replace(at, mark.size(), value);
  }
  return out;
}

}  // namespace dtlab::protocol
