// The study database's tables, v1 to v4, written once for both engines
// (schema_tables.h): what each migration adds, column by column. v1: studies,
// the ledger, sessions, planned trials, results, events, poses, questionnaire
// answers. v2: design hashes, the lab's decisions (exclusions and notes,
// appended with who, why and when), pauses, trial attempts and session
// claims (the one table changed in place: operational state, not data). v3:
// what the display did (warm-up and steady frames per trial, the display of
// each session start). v4: consent answers, withdrawals, the screen log.
// Only adds: a migration never drops or rewrites a column holding data.
#include <string>

#include "study/store/detail/schema_tables.h"

namespace dtlab::store::detail {
namespace {

using T = ColumnType;

// Invariant 8 (docs/store.md): the answer's shape follows its kind, and the score columns are
// exactly what store::score() computes (IEEE double division and the same tolerance on the
// distance on both engines). PostgreSQL has no IS for values and no boolean-as-integer.
Sql score_check() {
  auto both = [](bool pg) {
    const std::string flag = pg ? "(answered = 1)" : "answered";
    const std::string same = pg ? " IS NOT DISTINCT FROM " : " IS ";
    const std::string rel = pg ? "abs(answer_count - truth_count)::double precision / truth_count::double precision"
                               : "abs(answer_count - truth_count) * 1.0 / truth_count";
    const std::string correct = pg ? "(CASE WHEN answer_letter IS NULL THEN NULL\n"
                                     "                                             WHEN answer_letter = truth_letter "
                                     "THEN 1 ELSE 0 END)"
                                   : "(answer_letter = truth_letter)";
    return std::string(
               "-- The answer's shape follows its kind, and the score columns are exactly\n"
               "  -- what store::score() computes (score.h); see docs/store.md, invariant 8.\n"
               "  CHECK (CASE answer_kind\n"
               "    WHEN 'count' THEN\n"
               "      truth_count IS NOT NULL AND truth_letter IS NULL AND truth_x IS NULL AND truth_z IS NULL\n"
               "      AND answer_letter IS NULL AND answer_x IS NULL AND answer_z IS NULL\n"
               "      AND ") + flag + " = (answer_count IS NOT NULL)\n"
           "      AND correct IS NULL AND distance IS NULL\n"
           "      AND signed_error" + same + "answer_count - truth_count\n"
           "      AND rel_error" + same + "(CASE WHEN truth_count <> 0 THEN " + rel + " END)\n"
           "    WHEN 'letter' THEN\n"
           "      truth_letter IS NOT NULL AND truth_count IS NULL AND truth_x IS NULL AND truth_z IS NULL\n"
           "      AND answer_count IS NULL AND answer_x IS NULL AND answer_z IS NULL\n"
           "      AND " + flag + " = (answer_letter IS NOT NULL)\n"
           "      AND rel_error IS NULL AND signed_error IS NULL AND distance IS NULL\n"
           "      AND correct" + same + correct + "\n"
           "    WHEN 'position' THEN\n"
           "      truth_x IS NOT NULL AND truth_z IS NOT NULL AND truth_count IS NULL AND truth_letter IS NULL\n"
           "      AND answer_count IS NULL AND answer_letter IS NULL\n"
           "      AND (answer_x IS NULL) = (answer_z IS NULL) AND " + flag + " = (answer_x IS NOT NULL)\n"
           "      AND rel_error IS NULL AND signed_error IS NULL AND correct IS NULL\n"
           "      AND (distance IS NOT NULL) = " + flag + "\n"
           "      AND (distance IS NULL OR abs(distance * distance - ((answer_x - truth_x) * (answer_x - truth_x)\n"
           "            + (answer_z - truth_z) * (answer_z - truth_z)))\n"
           "          <= 1e-9 * (1 + (answer_x - truth_x) * (answer_x - truth_x) + (answer_z - truth_z) * (answer_z - truth_z)))\n"
           "  END)";
  };
  return {both(false), both(true)};
}

// A JSON object (the participant's demographics).
Sql json_object_check(const std::string& c) {
  return {"CHECK (json_valid(" + c + ") AND json_type(" + c + ") = 'object')",
          "CHECK (json_typeof(" + c + "::json) = 'object')"};
}

std::vector<Table> v1_tables() {
  return {
      {"studies", 1,
       {{"id", T::integer, "PRIMARY KEY"},
        {"protocol_id", T::text, "NOT NULL", "CHECK (length(protocol_id) > 0)"},
        {"protocol_text", T::text, "NOT NULL"},
        {"protocol_sha256", T::text, "NOT NULL", hex_check("protocol_sha256", 64)},
        {"software_version", T::text, "NOT NULL"},
        {"order_rows", T::integer, "NOT NULL", "CHECK (order_rows >= 1)"},
        {"created_at", T::text, "NOT NULL", iso_check("created_at")}}},
      {"study_factors", 1,
       {{"study_id", T::integer, "NOT NULL REFERENCES studies(id)"},
        {"position", T::integer, "NOT NULL", "CHECK (position >= 1)"},
        {"name", T::text, "NOT NULL", "CHECK (length(name) > 0)"}},
       {"PRIMARY KEY (study_id, position)", "UNIQUE (study_id, name)"},
       true},
      {"participants", 1,
       {{"id", T::integer, "PRIMARY KEY"},
        {"participant", T::text, "NOT NULL UNIQUE", "CHECK (length(participant) BETWEEN 1 AND 64)"},
        {"enrollment_index", T::integer, "NOT NULL UNIQUE", "CHECK (enrollment_index >= 0)"},
        {"order_row", T::integer, "NOT NULL", "CHECK (order_row >= 0)"},
        {"study_id", T::integer, "NOT NULL REFERENCES studies(id)"},
        {"demographics", T::text, "NOT NULL DEFAULT '{}'", json_object_check("demographics")},
        {"enrolled_at", T::text, "NOT NULL", iso_check("enrolled_at")},
        {"released_at", T::text, "", iso_check_nullable("released_at")}},
       {},
       false,
       {"CREATE INDEX participants_active_by_row ON participants(order_row) WHERE released_at IS NULL"}},
      {"sessions", 1,
       {{"id", T::integer, "PRIMARY KEY"},
        {"participant_id", T::integer, "NOT NULL UNIQUE REFERENCES participants(id)"},
        {"study_id", T::integer, "NOT NULL REFERENCES studies(id)"},
        {"software_version", T::text, "NOT NULL"},
        {"status", T::text, "NOT NULL", "CHECK (status IN ('running', 'finished', 'abandoned'))"},
        {"started_at", T::text, "NOT NULL", iso_check("started_at")},
        {"ended_at", T::text, "", iso_check_nullable("ended_at")}},
       {"CHECK ((status = 'running') = (ended_at IS NULL))"}},
      {"session_resumes", 1,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"resumed_at", T::text, "NOT NULL", iso_check("resumed_at")},
        {"software_version", T::text, "NOT NULL"},
        {"next_position", T::integer, "", "CHECK (next_position IS NULL OR next_position >= 1)"}},
       {},
       false,
       {"CREATE INDEX session_resumes_by_session ON session_resumes(session_id)"}},
      {"planned_trials", 1,
       {{"id", T::integer, "PRIMARY KEY"},
        {"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"position", T::integer, "NOT NULL", "CHECK (position >= 1)"},
        {"block", T::integer, "NOT NULL", "CHECK (block >= 1)"},
        {"task", T::text, "NOT NULL", "CHECK (length(task) > 0)"},
        {"trial", T::integer, "NOT NULL", "CHECK (trial >= 1)"},
        {"seed", T::text, "NOT NULL", digits_check("seed", 20)},
        {"method", T::text, "NOT NULL"},
        {"practice", T::integer, "NOT NULL", "CHECK (practice IN (0, 1))"}},
       {"UNIQUE (session_id, position)"}},
      {"planned_levels", 1,
       {{"planned_trial_id", T::integer, "NOT NULL REFERENCES planned_trials(id)"},
        {"factor_position", T::integer, "NOT NULL", "CHECK (factor_position >= 1)"},
        {"factor", T::text, "NOT NULL", "CHECK (length(factor) > 0)"},
        {"level", T::text, "NOT NULL"}},
       {"PRIMARY KEY (planned_trial_id, factor_position)", "UNIQUE (planned_trial_id, factor)"},
       true},
  };
}

Table trial_results() {
  return {"trial_results", 1,
          {{"planned_trial_id", T::integer, "PRIMARY KEY REFERENCES planned_trials(id)"},
           {"scene_hash", T::text, "NOT NULL", hex_check("scene_hash", 64)},
           {"answer_kind", T::text, "NOT NULL", "CHECK (answer_kind IN ('count', 'letter', 'position'))"},
           {"answered", T::integer, "NOT NULL", "CHECK (answered IN (0, 1))"},
           {"answer_count", T::integer, "", "CHECK (answer_count >= 0)"},
           {"answer_letter", T::text, "", "CHECK (length(answer_letter) > 0)"},
           {"answer_x", T::real},
           {"answer_z", T::real},
           {"truth_count", T::integer, "", "CHECK (truth_count >= 0)"},
           {"truth_letter", T::text, "", "CHECK (length(truth_letter) > 0)"},
           {"truth_x", T::real},
           {"truth_z", T::real},
           {"rel_error", T::real},
           {"signed_error", T::integer},
           {"correct", T::integer, "", "CHECK (correct IN (0, 1))"},
           {"distance", T::real, "", "CHECK (distance >= 0)"},
           {"completion_s", T::real, "NOT NULL", "CHECK (completion_s >= 0)"},
           {"started_at", T::text, "NOT NULL", iso_check("started_at")},
           {"ended_at", T::text, "NOT NULL", iso_check("ended_at")},
           {"frame_count", T::integer, "NOT NULL", "CHECK (frame_count >= 0)"},
           {"frame_ms_mean", T::real, "", "CHECK (frame_ms_mean >= 0)"},
           {"frame_ms_sd", T::real, "", "CHECK (frame_ms_sd >= 0)"},
           {"frame_ms_p95", T::real, "", "CHECK (frame_ms_p95 >= 0)"},
           {"frame_ms_max", T::real, "", "CHECK (frame_ms_max >= 0)"},
           {"event_count", T::integer, "NOT NULL", "CHECK (event_count >= 0)"},
           {"recorded_at", T::text, "NOT NULL", iso_check("recorded_at")},
           // v3: the warm-up frame apart from the steady frames, their median, how many were late
           // for the display, and the display's refresh rate.
           {"frame_first_ms", T::real, "", "CHECK (frame_first_ms IS NULL OR frame_first_ms >= 0)", 3},
           {"frame_ms_median", T::real, "", "CHECK (frame_ms_median IS NULL OR frame_ms_median >= 0)", 3},
           {"late_frames", T::integer, "", "CHECK (late_frames IS NULL OR late_frames >= 0)", 3},
           {"refresh_hz", T::real, "", "CHECK (refresh_hz IS NULL OR refresh_hz > 0)", 3}},
          {"CHECK (ended_at >= started_at)",
           "CHECK ((frame_count > 0) = (frame_ms_mean IS NOT NULL) AND (frame_count > 0) = (frame_ms_p95 IS NOT NULL)\n"
           "         AND (frame_count > 0) = (frame_ms_max IS NOT NULL) AND (frame_count > 1) = (frame_ms_sd IS NOT NULL))",
           score_check()}};
}

std::vector<Table> v1_records() {
  return {
      {"input_events", 1,
       {{"trial_id", T::integer, "NOT NULL REFERENCES trial_results(planned_trial_id)"},
        {"seq", T::integer, "NOT NULL", "CHECK (seq >= 1)"},
        {"t_s", T::real, "NOT NULL", "CHECK (t_s >= 0)"},
        {"kind", T::text, "NOT NULL",
         "CHECK (kind IN ('key_down', 'key_up', 'button_down', 'button_up', 'cursor', 'scroll', 'answer'))"},
        {"detail", T::text, "NOT NULL"},
        {"x", T::real, "NOT NULL"},
        {"y", T::real, "NOT NULL"}},
       {"PRIMARY KEY (trial_id, seq)"},
       true},
      {"camera_poses", 1,
       {{"trial_id", T::integer, "NOT NULL REFERENCES trial_results(planned_trial_id)"},
        {"frame", T::integer, "NOT NULL", "CHECK (frame >= 1)"},
        {"t_s", T::real, "NOT NULL", "CHECK (t_s >= 0)"},
        {"x", T::real, "NOT NULL"},
        {"y", T::real, "NOT NULL"},
        {"z", T::real, "NOT NULL"},
        {"yaw", T::real, "NOT NULL"},
        {"pitch", T::real, "NOT NULL"}},
       {"PRIMARY KEY (trial_id, frame)"},
       true},
      {"questionnaire_answers", 1,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"item", T::text, "NOT NULL", "CHECK (length(item) > 0)"},
        {"scope", T::text, "NOT NULL"},
        {"value_number", T::real},
        {"value_text", T::text},
        {"answered_at", T::text, "NOT NULL", iso_check("answered_at")}},
       {"CHECK ((value_number IS NULL) <> (value_text IS NULL))", "PRIMARY KEY (session_id, item, scope)"},
       true},
  };
}

std::vector<Table> v2_tables() {
  return {
      {"study_designs", 2,
       {{"study_id", T::integer, "PRIMARY KEY REFERENCES studies(id)"},
        {"design_sha256", T::text, "NOT NULL", hex_check("design_sha256", 64)}}},
      {"exclusions", 2,
       {{"id", T::integer, "PRIMARY KEY"},
        {"participant_id", T::integer, "NOT NULL REFERENCES participants(id)"},
        {"position", T::integer, "", "CHECK (position IS NULL OR position >= 1)"},
        {"action", T::text, "NOT NULL", "CHECK (action IN ('exclude', 'include'))"},
        {"reason", T::text, "NOT NULL"},
        {"decided_by", T::text, "NOT NULL"},
        {"decided_at", T::text, "NOT NULL", iso_check("decided_at")}},
       {"CHECK (action = 'include' OR length(trim(reason)) > 0)"},
       false,
       {"CREATE INDEX exclusions_by_participant ON exclusions(participant_id, position)"}},
      {"notes", 2,
       {{"id", T::integer, "PRIMARY KEY"},
        {"participant_id", T::integer, "REFERENCES participants(id)"},
        {"position", T::integer, "", "CHECK (position IS NULL OR position >= 1)"},
        {"author", T::text, "NOT NULL"},
        {"text", T::text, "NOT NULL", "CHECK (length(trim(text)) > 0)"},
        {"written_at", T::text, "NOT NULL", iso_check("written_at")}},
       {"CHECK (position IS NULL OR participant_id IS NOT NULL)"}},
      {"session_pauses", 2,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"position", T::integer, "", "CHECK (position IS NULL OR position >= 1)"},
        {"paused_at", T::text, "NOT NULL", iso_check("paused_at")},
        {"resumed_at", T::text, "NOT NULL", iso_check("resumed_at")},
        {"duration_s", T::real, "NOT NULL", "CHECK (duration_s >= 0)"}},
       {"CHECK (resumed_at >= paused_at)"},
       false,
       {"CREATE INDEX session_pauses_by_session ON session_pauses(session_id)"}},
      {"trial_attempts", 2,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"position", T::integer, "NOT NULL", "CHECK (position >= 1)"},
        {"attempt", T::integer, "NOT NULL", "CHECK (attempt >= 1)"},
        {"started_at", T::text, "NOT NULL", iso_check("started_at")},
        {"owner", T::text, "NOT NULL"}},
       {"PRIMARY KEY (session_id, position, attempt)"},
       true},
      {"session_claims", 2,
       {{"session_id", T::integer, "PRIMARY KEY REFERENCES sessions(id)"},
        {"owner", T::text, "NOT NULL", "CHECK (length(owner) > 0)"},
        {"host", T::text, "NOT NULL"},
        {"pid", T::integer, "NOT NULL"},
        {"claimed_at", T::text, "NOT NULL", iso_check("claimed_at")},
        {"heartbeat_at", T::text, "NOT NULL", iso_check("heartbeat_at")},
        {"expires_at", T::text, "NOT NULL", iso_check("expires_at")}}},
  };
}

std::vector<Table> v3_v4_tables() {
  return {
      {"session_displays", 3,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"recorded_at", T::text, "NOT NULL", iso_check("recorded_at")},
        {"kind", T::text, "NOT NULL", "CHECK (kind IN ('window', 'headless'))"},
        {"width", T::integer, "NOT NULL", "CHECK (width >= 1)"},
        {"height", T::integer, "NOT NULL", "CHECK (height >= 1)"},
        {"refresh_hz", T::real, "", "CHECK (refresh_hz IS NULL OR refresh_hz > 0)"},
        {"renderer", T::text, "NOT NULL"},
        {"monitor", T::text, "NOT NULL"}},
       {},
       false,
       {"CREATE INDEX session_displays_by_session ON session_displays(session_id)"}},
      {"consents", 4,
       {{"participant_id", T::integer, "PRIMARY KEY REFERENCES participants(id)"},
        {"agreed", T::integer, "NOT NULL", "CHECK (agreed IN (0, 1))"},
        {"text_sha256", T::text, "NOT NULL", hex_check("text_sha256", 64)},
        {"answered_at", T::text, "NOT NULL", iso_check("answered_at")}}},
      {"withdrawals", 4,
       {{"id", T::integer, "PRIMARY KEY"},
        {"participant_id", T::integer, "NOT NULL UNIQUE REFERENCES participants(id)"},
        {"withdrawn_at", T::text, "NOT NULL", iso_check("withdrawn_at")},
        {"reason", T::text, "NOT NULL", "CHECK (length(trim(reason)) > 0)"},
        {"decided_by", T::text, "NOT NULL"}}},
      {"screens", 4,
       {{"session_id", T::integer, "NOT NULL REFERENCES sessions(id)"},
        {"seq", T::integer, "NOT NULL", "CHECK (seq >= 1)"},
        {"screen", T::text, "NOT NULL", "CHECK (length(screen) > 0)"},
        {"shown", T::text, "NOT NULL"},
        {"shown_at", T::text, "NOT NULL", iso_check("shown_at")},
        {"ended_at", T::text, "NOT NULL", iso_check("ended_at")},
        {"duration_s", T::real, "NOT NULL", "CHECK (duration_s >= 0)"},
        {"answer", T::text}},
       {"CHECK (ended_at >= shown_at)", "PRIMARY KEY (session_id, seq)"},
       true},
  };
}

std::vector<Table> all_tables() {
  std::vector<Table> t{{"schema_migrations", 0,
                        {{"version", T::integer, "PRIMARY KEY", "CHECK (version >= 1)"},
                         {"description", T::text, "NOT NULL"},
                         {"applied_at", T::text, "NOT NULL", iso_check("applied_at")},
                         {"software_version", T::text, "NOT NULL"}}}};
  for (auto part : {v1_tables(), std::vector<Table>{trial_results()}, v1_records(), v2_tables(), v3_v4_tables()})
    for (Table& table : part) t.push_back(std::move(table));
  return t;
}

}  // namespace

const std::vector<Table>& schema_tables() {
  static const std::vector<Table> tables = all_tables();
  return tables;
}

}  // namespace dtlab::store::detail
