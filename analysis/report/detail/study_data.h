// Everything the report reads from a study database, as plain values: the
// current protocol (text, parsed), the participant ledger with sessions and
// demographics, every recorded trial (the trial_table view) and the
// questionnaire answers. Reads through SQLite with SQLITE_OPEN_READONLY inside
// one read transaction (a consistent snapshot while a session writes); never
// writes. Errors name the file; SQLite failures carry field "sqlite".
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/protocol/protocol.h"

namespace dtlab::report::detail {

struct TrialRow {
  std::string participant;
  int enrollment_index = 0;
  int order_row = 0;
  std::string session_status;
  int position = 0, block = 0;
  std::vector<std::string> levels;  // per protocol factor, in protocol order ("" if absent)
  std::vector<int> level_index;     // index into the factor's levels; -1 if unknown
  std::string task;
  int trial = 0;
  bool practice = false;
  std::string method;
  std::optional<std::int64_t> answer_count, truth_count, signed_error;
  std::optional<std::string> answer_letter, truth_letter;
  std::optional<double> answer_x, answer_z, truth_x, truth_z;
  std::optional<double> rel_error, distance;
  std::optional<bool> correct;
  double time_s = 0;
  std::int64_t frame_count = 0;
  std::optional<double> frame_mean, frame_sd, frame_p95, frame_max;
  std::string protocol_sha256;
};

struct ParticipantRow {
  std::string id;
  int index = 0, order_row = 0;
  bool released = false;
  std::map<std::string, std::string> demographics;  // values as text
  std::string session_status;                       // "" when no session was started
  int planned = 0, recorded = 0, resumes = 0;
  std::string software_version;                     // of the session
};

struct AnswerRow {
  std::string participant;
  std::string item, scope;
  std::optional<double> number;
  std::optional<std::string> text;
};

struct StudyData {
  std::string path;
  protocol::Protocol protocol;  // the current (latest) protocol of the file
  std::string software_version; // that study's software version
  int studies = 1;              // protocol records in the file (> 1 after an allowed protocol change)
  std::vector<ParticipantRow> participants;  // enrollment order
  std::vector<TrialRow> trials;              // every recorded trial of the current protocol, by index, position
  long long other_protocol_trials = 0;       // recorded under an earlier protocol (not analysed)
  std::vector<AnswerRow> answers;            // questionnaire answers of the current protocol's sessions
};

// Reads the database at `path` (which must be a dtlab database: callers check
// with store::export_trials_csv first, which names what is wrong).
Result<StudyData> read_study(const std::string& path);

}  // namespace dtlab::report::detail
