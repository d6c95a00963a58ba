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
    // Instructions before a task set, and training.
    TextKey{"instructions.next_task", "Next task", ""},
    TextKey{"instructions.welcome_back", "Welcome back", ""},
    TextKey{"instructions.practise_first", "First you can practise freely in a scene like the ones to come.", ""},
    TextKey{"instructions.count_targets",
            "Count all the RED objects in the scene. Drag with the left mouse button to turn the scene around its "
            "centre. When you know how many there are, press Enter and type the number.",
            ""},
    TextKey{"instructions.identify_letter",
            "The red CONES form one of the letters C, K, R, X or Y. Other red objects are not part of it. Drag with "
            "the left mouse button to turn the scene. When you know the letter, press Enter and choose it.",
            ""},
    TextKey{"instructions.find_unique",
            "Find the object shown in the upper left corner. Move with the arrow keys (Up, Down), turn with the mouse "
            "or Left/Right. When you have found it, press Enter and click where it is on the floor plan.",
            ""},
    TextKey{"instructions.count_kind",
            "Count the objects of the kind shown in the upper left corner, in the whole building. Move with the arrow "
            "keys (Up, Down), turn with the mouse or Left/Right. When you are done, press Enter and type the number.",
            ""},
    TextKey{"training.bar", "Practice: explore freely ({time} left). Press Enter to start.", "time"},
    TextKey{"training.start", "Start the trials", ""},
    // The trial and its answer.
    TextKey{"trial.bar", "Press Enter when you have your answer.", ""},
    TextKey{"trial.answer", "Answer", ""},
    TextKey{"trial.find_this", "Find this:", ""},
    TextKey{"trial.paused_title", "Paused", ""},
    TextKey{"trial.paused_text", "The experimenter paused the session. Please wait.", ""},
    TextKey{"trial.paused_button", "Waiting...", ""},
    TextKey{"answer.count", "How many red objects?", ""},
    TextKey{"answer.letter", "Which letter do the red cones form?", ""},
    TextKey{"answer.position", "Where is the {kind}? Click its place on the floor plan.", "kind"},
    TextKey{"answer.kind_count", "How many of this kind ({kind}) in the building?", "kind"},
    TextKey{"answer.done", "Done", ""},
    TextKey{"answer.confirm", "Confirm", ""},
    TextKey{"answer.whole_number", "Type a whole number, then press Enter.", ""},
    TextKey{"answer.back", "Escape: back to the scene", ""},
    TextKey{"answer.start", "start", ""},
    // Questionnaire pages (every item type), the depth test.
    TextKey{"question.progress", "Question {n} of {total}", "n total"},
    TextKey{"question.next", "Next", ""},
    TextKey{"question.value", "Value", ""},
    TextKey{"question.characters", "{used} of {max} characters. Next, or Ctrl+Enter, when done.", "used max"},
    TextKey{"question.choose", "Choose {min} to {max}.", "min max"},
    TextKey{"question.number", "Enter a number from {min} to {max}.", "min max"},
    TextKey{"depth_test.pair", "{progress}. Pair {pair} of {pairs}", "progress pair pairs"},
    TextKey{"depth_test.click", "Click A or B (or press the key).", ""},
    // The kinds of WALKTHROUGH objects, as the "find this" panel and the questions name them.
    TextKey{"kind.dog", "dog", ""},
    TextKey{"kind.cat", "cat", ""},
    TextKey{"kind.bird", "bird", ""},
    TextKey{"kind.fish", "fish", ""},
    TextKey{"kind.car", "car", ""},
    TextKey{"kind.bike", "bike", ""},
    TextKey{"kind.truck", "truck", ""},
    TextKey{"kind.motorbike", "motorbike", ""},
    TextKey{"kind.table", "table", ""},
    TextKey{"kind.chair", "chair", ""},
    TextKey{"kind.sofa", "sofa", ""},
    TextKey{"kind.bed", "bed", ""},
    TextKey{"kind.lamp", "lamp", ""},
    TextKey{"kind.directors_chair", "director's chair", ""},
    // The end of the session.
    TextKey{"end.title", "Thank you!", ""},
    TextKey{"end.text", "The session is complete. Thank you for taking part.", ""},
    TextKey{"end.experimenter", "(Experimenter: close with the button or Escape.)", ""},
    TextKey{"end.close", "Close", ""},
    TextKey{"end.aborted_title", "Session aborted", ""},
    TextKey{"end.aborted_text", "The experimenter ended this session.", ""},
    TextKey{"end.failed_title", "Session interrupted", ""},
    TextKey{"end.failed_text", "A technical problem stopped the session. Everything you finished is saved. Please tell the experimenter.", ""},
    TextKey{"end.failed_experimenter", "(Experimenter: {error}. Run the same command again to resume the session.)", "error"},
    // The experimenter's start screen.
    TextKey{"start.participant", "Participant", ""},
    TextKey{"start.id", "Participant ID", ""},
    TextKey{"start.start", "Start session", ""},
    TextKey{"start.choose", "(choose)", ""},
    TextKey{"start.type_id", "Type the participant's ID first.", ""},
    TextKey{"start.finished", "Participant \"{id}\" has finished their session; a finished session cannot run again. Use a new ID.", "id"},
    TextKey{"start.released", "Participant \"{id}\" was released (their session is abandoned); enroll them under a new ID.", "id"},
    TextKey{"start.running", "Running sessions (interrupted, or running at another station):", ""},
    TextKey{"start.resume", "Resume {id}", "id"},
    TextKey{"start.release", "Release {id}...", "id"},
    TextKey{"start.really_release", "Really release {id} (abandoned)", "id"},
    TextKey{"start.released_now", "Released {id}: the session is abandoned and its order row free.", "id"},
    TextKey{"start.quit", "Quit", ""},
    TextKey{"start.order_row", "Order row", ""},
    TextKey{"start.enrolled", "Enrolled", ""},
    TextKey{"start.finished_count", "Finished", ""},
    TextKey{"start.running_count", "Running", ""},
    TextKey{"start.abandoned_count", "Abandoned", ""},
    TextKey{"start.design",
            "{conditions} conditions ordered by {scheme} ({rows} order rows); {trials} trials per participant; "
            "{participants} participants planned.",
            "conditions scheme rows trials participants"},
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

std::string level_text(const Protocol& p, std::string_view factor, std::string_view level) {
  if (const Factor* f = find_factor(p, factor))
    for (std::size_t i = 0; i < f->levels.size(); ++i)
      if (f->levels[i] == level) return level_label(*f, static_cast<int>(i));
  return std::string(level);
}

std::string participant_text(const Protocol& p) {
  std::string all = p.title + "\n";
  const auto add = [&](std::string_view t) { all.append(t); all += "\n"; };
  for (const TextKey& k : kKeys) add(k.english);
  for (const auto& [key, value] : p.text) add(value);
  for (const Factor& f : p.factors) {
    for (const std::string& l : f.labels) add(l);
    for (const std::string& i : f.instructions) add(i);
  }
  if (p.flow.consent) {
    add(p.flow.consent->title);
    add(p.flow.consent->text);
  }
  for (const Page& page : p.flow.pages) {
    add(page.title);
    add(page.text);
  }
  for (const Scenario& s : p.scenarios)
    for (const Task& t : s.tasks) add(t.instructions);
  for (const QuestionnaireItem& q : p.questionnaire) {
    add(q.prompt);
    for (const auto& [key, value] : q.keys) {  // options, labels, anchors, units: whatever text it shows
      if (const auto* text = std::get_if<std::string>(&value)) add(*text);
      if (const auto* texts = std::get_if<std::vector<std::string>>(&value))
        for (const std::string& t : *texts) add(t);
    }
  }
  for (const DemographicField& d : p.demographics) {
    add(d.prompt);
    for (const std::string& o : d.options) add(o);
  }
  return all;
}

}  // namespace dtlab::protocol
