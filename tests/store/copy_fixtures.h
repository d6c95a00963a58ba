// The studies the copy and merge tests write and the reads they compare
// with: one participant's session with everything a session records, a study
// holding every table, the lab's database before a station takes its copy,
// and every table of the schema read through the engines' own C APIs (reals
// spelled alike on both engines). Pure test fixtures: nothing here asserts a
// property of the copy.
#pragma once
#include <gtest/gtest.h>

#include <charconv>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "study/store/export.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store::testing {

// The display of a station's window (schema v3), with a monitor name CSV and SQL would quote.
inline const DisplayInfo kWindow{"window", 1920, 1080, 143.98, "4.6 (Core Profile) Mesa 22.3.6 / llvmpipe", "DELL U2720Q, \"left\""};

// Runs one participant's session on kWindow: `n` trials recorded (all: finished), with an
// interrupted attempt and a pause in trial 2; every other trial knows the display's refresh rate.
inline void run_participant(Store& s, const std::string& id, int n, Demographics demo = {}) {
  auto e = s.enroll(id, demo);
  ASSERT_TRUE(e) << e.error().to_string();
  const design::Plan plan = make_plan(e->index, e->order_row, 1);
  auto ses = s.begin_session(id, plan);
  ASSERT_TRUE(ses) << ses.error().to_string();
  ASSERT_TRUE(s.record_display(*ses, kWindow));
  ASSERT_TRUE(s.record_screen(*ses, {"instructions T1", "T1", at_ms(1'700'000'000'000), at_ms(1'700'000'004'500),
                                     std::string("continue")}));
  for (int i = 0; i < n; ++i) {
    const auto& t = plan.trials[static_cast<std::size_t>(i)];
    ASSERT_TRUE(s.begin_trial(*ses, t.position));
    if (i == 1) {
      ASSERT_TRUE(s.begin_trial(*ses, t.position));  // the first attempt reads as interrupted
      ASSERT_TRUE(s.record_pause(*ses, t.position, at_ms(1'700'000'500'000), at_ms(1'700'000'507'250)));
    }
    const std::optional<double> hz = i % 2 ? std::nullopt : kWindow.refresh_hz;
    ASSERT_TRUE(s.record_trial(*ses, make_record(static_cast<std::uint64_t>(e->index) + 3, t, 7 + i, hz)));
  }
  if (n == static_cast<int>(plan.trials.size())) {
    ASSERT_TRUE(s.finish_session(*ses));
    ASSERT_TRUE(s.record_questionnaire(*ses, {{"rating", "transparency=on", 4.0}, {"comment", "", std::string("ok, \"fine\"")}}));
    ASSERT_TRUE(s.record_screen(*ses, {"page debrief", "debrief", at_ms(1'700'001'000'000), at_ms(1'700'001'020'000),
                                       std::nullopt}));
  }
}

inline const std::string kConsentText = std::string(64, 'c');  // the SHA-256 of the consent text shown

// A study with everything a study holds: two protocol texts of one design, finished, running,
// resumed and released sessions, a participant never started, exclusions and an inclusion, notes,
// the displays sessions ran on and frame times with and without the display's refresh rate, a
// consent, a declined consent, a withdrawal after a finished session and the screen log.
inline void write_rich_study(const std::string& where) {
  StudyInfo a = study_info("id = \"test2x2\"\n# first wording\n");
  a.design_sha256 = std::string(64, 'd');
  StudyInfo b = study_info("id = \"test2x2\"\n# second wording\n");
  b.design_sha256 = a.design_sha256;
  {
    Store s = open_ok(where, a);
    ASSERT_TRUE(s.record_consent("P1", {{"age", "31"}, {"hand", "left"}}, true, kConsentText));
    run_participant(s, "P1", 4);
    run_participant(s, "P2", 2);
    run_participant(s, "P,3 \"q\"", 1);
    ASSERT_TRUE(s.release("P,3 \"q\""));
  }
  Store s = open_ok(where, b);  // a reworded protocol: a second study row, same design
  auto e = s.lookup("P2");
  auto ses = s.begin_session("P2", make_plan(e->index, e->order_row, 1));  // resumed
  ASSERT_TRUE(ses && ses->resumed);
  ASSERT_TRUE(s.record_display(*ses, DisplayInfo{"headless", 800, 600, std::nullopt, "OSMesa", ""}));
  ASSERT_TRUE(s.record_trial(*ses, make_record(9, **s.next_trial(*ses), 3)));
  ASSERT_TRUE(s.release_claim(*ses));
  run_participant(s, "P4", 4);
  ASSERT_TRUE(s.enroll("P5", {{"simulated", "true"}}));  // never started
  ASSERT_TRUE(s.exclude("P1", std::nullopt, "misunderstood", "RA"));
  ASSERT_TRUE(s.include("P1", std::nullopt, "", "PI"));
  ASSERT_TRUE(s.exclude("P4", 3, "fire alarm", "RA"));
  ASSERT_TRUE(s.add_note("P1", 2, "RA", "sneezed"));
  ASSERT_TRUE(s.add_note("", std::nullopt, "PI", "room too warm"));
  ASSERT_TRUE(s.record_consent("D", {{"age", "50"}}, false, kConsentText));  // declined: only the refusal
  ASSERT_TRUE(s.withdraw("P4", "asked by email", "PI"));                     // finished, then withdrew
}

// Every table of the schema with an order that is the same on both engines.
inline const std::vector<std::pair<std::string, std::string>> kTables = {
    {"schema_migrations", "version"},
    {"studies", "id"},
    {"study_factors", "study_id, position"},
    {"study_designs", "study_id"},
    {"participants", "id"},
    {"sessions", "id"},
    {"session_resumes", "session_id, resumed_at"},
    {"planned_trials", "id"},
    {"planned_levels", "planned_trial_id, factor_position"},
    {"trial_results", "planned_trial_id"},
    {"input_events", "trial_id, seq"},
    {"camera_poses", "trial_id, frame"},
    {"questionnaire_answers", "session_id, item, scope"},
    {"exclusions", "id"},
    {"notes", "id"},
    {"session_pauses", "session_id, paused_at"},
    {"trial_attempts", "session_id, position, attempt"},
    {"session_displays", "session_id, recorded_at, kind"},
    {"consents", "participant_id"},
    {"withdrawals", "id"},
    {"screens", "session_id, seq"},
};

// A table's rows with every real spelled the same way on both engines (17 significant digits).
inline std::vector<std::vector<std::string>> table(RawDb& db, const std::string& name, const std::string& order) {
  auto rows = db.rows("SELECT * FROM " + name + " ORDER BY " + order);
  for (auto& row : rows)
    for (std::string& v : row) {
      if (v.find_first_of(".eE") == std::string::npos || v.find_first_not_of("0123456789.eE+-") != std::string::npos)
        continue;
      double d = 0;
      if (std::from_chars(v.data(), v.data() + v.size(), d).ec != std::errc()) continue;
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", d);
      v = buf;
    }
  return rows;
}

inline std::string exported(const std::string& where) {
  std::ostringstream out;
  auto sum = export_trials_csv(where, out);
  EXPECT_TRUE(sum) << sum.error().to_string();
  return out.str();
}

// Parameter: the engine of the source; the copy goes to the other engine and back.
// Everything in a database, for "nothing was written".
inline std::vector<std::vector<std::vector<std::string>>> dump(const std::string& where) {
  RawDb db(where);
  std::vector<std::vector<std::vector<std::string>>> out;
  for (const auto& [name, order] : kTables) out.push_back(table(db, name, order));
  return out;
}

// The lab's server before a station goes offline: `n` participants P1.. finished, rows 0..n-1.
inline std::string lab_with(const std::string& where, int n = 3) {
  Store s = open_ok(where);
  for (int i = 1; i <= n; ++i) run_participant(s, "P" + std::to_string(i), 4);
  return where;
}

}  // namespace dtlab::store::testing
