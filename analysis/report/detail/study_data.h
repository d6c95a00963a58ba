// Everything the report reads from a study database, as plain values, for
// ONE design revision (docs/store.md, "Protocol revisions"): the latest
// protocol text of that revision (parsed), the participants whose session
// (or enrollment) belongs to it, their recorded trials and questionnaire
// answers, and the lab's exclusions. Read through the store's StudyReader
// (one snapshot); never writes. Excluded data are left out unless asked for.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"
#include "study/store/read.h"

namespace dtlab::report::detail {

// A recorded trial as the report reads it: the store's row itself (participant, enrollment index,
// order row, session status, the plan in `planned`, the result -- answer, truth, completion_s,
// frames --, scores, protocol hash, exclusion), which the sections read directly, and what
// read_study derives from the protocol and the sessions: the levels in protocol factor order and
// the display the trial ran on. Never a second copy of a field the store's row holds.
struct TrialRow : store::TrialRow {
  std::vector<std::string> levels;  // per protocol factor, in protocol order ("" if absent)
  std::vector<int> level_index;     // index into the factor's levels; -1 if unknown
  std::string display_kind;                 // the session's display at the trial: "window", "headless"; "" unknown
  int display_width = 0, display_height = 0;  // its framebuffer pixels (0 = not recorded)
  std::string renderer;                     // "GL_VERSION / GL_RENDERER" of that display
};

// The number of a count answer or truth (T1, T4); nullopt for none or another kind of answer.
std::optional<std::int64_t> count_of(const std::optional<store::Answer>& a);

struct ParticipantRow {
  std::string id;
  int index = 0, order_row = 0;
  bool released = false;
  std::map<std::string, std::string> demographics;  // values as text
  std::optional<store::SessionStatus> session_status;  // nullopt when no session was started
  int planned = 0, recorded = 0, resumes = 0;
  std::string software_version;                     // of the session
  int pauses = 0;                                   // the experimenter's pauses of the session
  double paused_s = 0;                              // their total length
  std::vector<std::string> notes;                   // the experimenter's notes about them ("trial 3: ..." for a trial's)
};

struct AnswerRow {
  std::string participant;
  std::string item, scope;
  std::optional<double> number;
  std::optional<std::string> text;
};

struct StudyData {
  std::string path;
  protocol::Protocol protocol;  // the latest protocol text of the analysed design revision
  std::string software_version; // the software that recorded that text
  int design_revision = 1;      // the analysed one, 1-based
  int design_revisions = 1;     // distinct designs in the file (> 1 after an allowed design change)
  int protocol_texts = 1;       // protocol texts of the analysed design (rewordings share a design)
  std::vector<ParticipantRow> participants;  // of the analysed design, enrollment order
  std::vector<TrialRow> trials;              // their recorded trials, by index, position
  long long other_revision_trials = 0;       // recorded under another design revision (not analysed here)
  std::vector<AnswerRow> answers;            // questionnaire answers of the analysed participants
  std::vector<store::Exclusion> exclusions;  // every decision about the analysed participants, in order
  std::vector<std::string> study_notes;      // notes about the study as a whole, in order
  // Participants of the design who withdrew their consent (declined it, or withdrew later): never
  // analysed, not even with_excluded, and not among `participants`; counted here.
  std::vector<std::string> withdrawn;
  int declined = 0;                          // of those, the ones who declined consent on its page
  int consented = 0;                         // participants who agreed on the consent page
  std::vector<std::string> excluded_participants;  // excluded now (left out unless with_excluded)
  long long excluded_trials = 0;             // recorded trials excluded now (theirs or their participant's)
  bool with_excluded = false;                // excluded data are kept in `trials` and `answers`
};

// The 1-based design revisions of the database, with their latest revision row each.
Result<std::vector<store::Revision>> design_revisions(store::StudyReader& reader);

// Which design revisions `spec` ("all", "latest", "N") names, of `count` (messages name `path`).
Result<std::vector<int>> chosen_revisions(const std::string& spec, int count, const std::string& path);

// Reads design revision `revision` (1-based) of the database, its trials from `trials` (reader.trials(),
// read once by the caller for every revision and the export). Excluded participants and trials
// are dropped from `trials` and `answers` unless `with_excluded`.
Result<StudyData> read_study(store::StudyReader& reader, const std::vector<store::TrialRow>& trials, int revision,
                             bool with_excluded);
// The same, reading the trials itself.
Result<StudyData> read_study(store::StudyReader& reader, int revision, bool with_excluded);

}  // namespace dtlab::report::detail
