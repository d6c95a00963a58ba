// The typed reader (study/store/read.h), on both engines: everything a
// session writes comes back as plain structs from one snapshot -- revisions,
// ledger, sessions with resumes, pauses and interruptions, plans, results,
// questionnaire, exclusions, notes, poses and events, the displays and frame
// timing of schema v3 -- and reading never writes: not to a read-only file,
// not on read-only media (a directory this process cannot write), and no
// -wal/-shm is left behind. Expected values come from the fixtures' inputs,
// never from the reader itself.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "study/store/read.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;
namespace fs = std::filesystem;

StudyReader read_ok(const std::string& path, ReadOptions o = {}) {
  auto r = StudyReader::open(path, o);
  if (!r) {
    ADD_FAILURE() << r.error().to_string();
    std::abort();
  }
  return std::move(*r);
}

// P1: 3 of 4 trials (an interrupted attempt of trial 2, a pause in trial 3), the questionnaire,
// a note; P2: enrolled with demographics, 1 trial, released.
void write_study(const std::string& path) {
  Store s = open_ok(path);
  auto e1 = s.enroll("P1", {{"age", "31"}, {"handedness", "left"}});
  ASSERT_TRUE(e1);
  const design::Plan plan = make_plan(e1->index, e1->order_row, 1);
  auto ses = s.begin_session("P1", plan);
  ASSERT_TRUE(ses);
  ASSERT_TRUE(s.begin_trial(*ses, 1));
  ASSERT_TRUE(s.record_trial(*ses, make_record(9, plan.trials[0], 5)));
  ASSERT_TRUE(s.begin_trial(*ses, 2));  // attempt 1 of trial 2 dies with the process ...
  ASSERT_TRUE(s.begin_trial(*ses, 2));  // ... attempt 2 re-runs it from its start
  ASSERT_TRUE(s.record_trial(*ses, make_record(9, plan.trials[1], 4)));
  ASSERT_TRUE(s.begin_trial(*ses, 3));
  ASSERT_TRUE(s.record_pause(*ses, 3, at_ms(1'700'000'300'000), at_ms(1'700'000'312'500)));
  ASSERT_TRUE(s.record_trial(*ses, make_record(9, plan.trials[2], 3)));
  ASSERT_TRUE(s.record_questionnaire(*ses, {{"rating", "scenario=ABSTRACT", 3.0}, {"preference", "", "on"}}));
  ASSERT_TRUE(s.add_note("P1", 2, "RA", "participant sneezed"));
  ASSERT_TRUE(s.add_note("", std::nullopt, "PI", "room too warm today"));
  auto e2 = s.enroll("P2", {{"simulated", "true"}});
  ASSERT_TRUE(e2);
  const design::Plan plan2 = make_plan(e2->index, e2->order_row, 1);
  auto ses2 = s.begin_session("P2", plan2);
  ASSERT_TRUE(ses2);
  ASSERT_TRUE(s.record_trial(*ses2, make_record(9, plan2.trials[0], 2)));
  ASSERT_TRUE(s.release("P2"));
  ASSERT_TRUE(s.exclude("P1", 2, "sneezed", "RA"));
}

class Read : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Read);

TEST_P(Read, EverythingASessionWroteComesBackAsStructs) {
  const std::string path = study();
  write_study(path);
  StudyReader r = read_ok(path);
  EXPECT_EQ(r.schema_version(), kSchemaVersion);

  auto revs = r.revisions();
  ASSERT_TRUE(revs) << revs.error().to_string();
  ASSERT_EQ(revs->size(), 1u);
  EXPECT_EQ((*revs)[0].protocol_text, study_info().protocol_text);
  EXPECT_EQ((*revs)[0].factors, (std::vector<std::string>{"transparency", "scenario"}));
  EXPECT_EQ((*revs)[0].order_rows, 4);

  auto ledger = r.ledger();
  ASSERT_TRUE(ledger);
  ASSERT_EQ(ledger->size(), 2u);
  EXPECT_EQ((*ledger)[0].participant, "P1");
  EXPECT_EQ((*ledger)[0].demographics, (Demographics{{"age", "31"}, {"handedness", "left"}}));
  EXPECT_FALSE((*ledger)[0].simulated());
  EXPECT_TRUE((*ledger)[1].simulated());
  EXPECT_TRUE((*ledger)[1].released_at.has_value());
  EXPECT_EQ((*ledger)[1].index, 1);
  EXPECT_EQ((*ledger)[1].order_row, 1);

  auto sessions = r.sessions();
  ASSERT_TRUE(sessions);
  ASSERT_EQ(sessions->size(), 2u);
  const SessionRecord& s1 = (*sessions)[0];
  EXPECT_EQ(s1.status, SessionStatus::running);
  EXPECT_EQ(s1.planned, 4);
  EXPECT_EQ(s1.recorded, 3);
  ASSERT_EQ(s1.pauses.size(), 1u);
  EXPECT_EQ(s1.pauses[0].position, 3);
  EXPECT_DOUBLE_EQ(s1.pauses[0].duration_s, 12.5);
  EXPECT_DOUBLE_EQ(s1.paused_s(), 12.5);
  EXPECT_EQ(s1.pauses[0].paused_at, "2023-11-14T22:18:20.000Z");
  ASSERT_EQ(s1.interruptions.size(), 1u);  // attempt 1 of trial 2
  EXPECT_EQ(s1.interruptions[0].position, 2);
  EXPECT_EQ(s1.interruptions[0].attempt, 1);
  EXPECT_FALSE(s1.claim.has_value());  // the writing Store released its claim when it was destroyed
  EXPECT_EQ((*sessions)[1].status, SessionStatus::abandoned);

  auto planned = r.planned("P1");
  ASSERT_TRUE(planned);
  ASSERT_EQ(planned->size(), 4u);
  const design::Plan plan = make_plan(0, 0, 1);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(same_trial((*planned)[i].trial, plan.trials[i])) << i;

  auto trials = r.trials();
  ASSERT_TRUE(trials);
  ASSERT_EQ(trials->size(), 4u);
  const TrialRecord want = make_record(9, plan.trials[1], 4);
  const TrialRow& t2 = (*trials)[1];
  EXPECT_EQ(t2.participant, "P1");
  EXPECT_TRUE(same_trial(t2.planned, plan.trials[1]));
  EXPECT_EQ(t2.scene_hash, want.scene_hash);
  EXPECT_EQ(t2.completion_s, want.completion_s);
  EXPECT_EQ(std::get<Letter>(t2.truth).letter, "K");  // position 2 is a T2
  EXPECT_EQ(t2.answer.has_value(), want.answer.has_value());
  EXPECT_EQ(t2.frames.frames, 4);
  EXPECT_EQ(t2.event_count, 20);
  EXPECT_EQ(t2.excluded, std::optional<std::string>("sneezed"));
  EXPECT_FALSE((*trials)[0].excluded.has_value());
  EXPECT_EQ(t2.level("transparency"), "on");  // block 2 of order row 0 is condition 1 (on, ABSTRACT)
  EXPECT_EQ(t2.level("no such factor"), "");
  EXPECT_EQ((*trials)[3].session_status, SessionStatus::abandoned);

  auto q = r.questionnaire("P1");
  ASSERT_TRUE(q);
  ASSERT_EQ(q->size(), 2u);
  EXPECT_EQ((*q)[0].item, "preference");  // by item, then scope
  EXPECT_EQ(std::get<std::string>((*q)[0].value), "on");
  EXPECT_EQ((*q)[1].item, "rating");
  EXPECT_EQ((*q)[1].scope, "scenario=ABSTRACT");
  EXPECT_EQ(std::get<double>((*q)[1].value), 3.0);

  auto x = r.exclusions();
  ASSERT_TRUE(x);
  ASSERT_EQ(x->size(), 1u);
  EXPECT_EQ((*x)[0].participant, "P1");
  EXPECT_EQ((*x)[0].position, 2);
  EXPECT_TRUE((*x)[0].exclude);
  EXPECT_EQ((*x)[0].by, "RA");

  auto notes = r.notes();
  ASSERT_TRUE(notes);
  ASSERT_EQ(notes->size(), 2u);
  EXPECT_EQ((*notes)[0].text, "participant sneezed");
  EXPECT_EQ((*notes)[1].participant, "");

  auto poses = r.poses("P1", 1);
  ASSERT_TRUE(poses);
  const TrialRecord r1 = make_record(9, plan.trials[0], 5);
  ASSERT_EQ(poses->size(), r1.poses.size());
  EXPECT_EQ((*poses)[4].z, r1.poses[4].z);
  EXPECT_EQ((*poses)[4].yaw, r1.poses[4].yaw);
  auto events = r.events("P1", 1);
  ASSERT_TRUE(events);
  ASSERT_EQ(events->size(), r1.events.size());
  EXPECT_EQ((*events)[3].detail, r1.events[3].detail);
  EXPECT_EQ((*events)[3].kind, r1.events[3].kind);
  auto none = r.poses("P1", 4);  // planned, not recorded
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().kind, ErrorKind::not_found);

  auto ok = r.integrity_check();
  ASSERT_TRUE(ok);
  EXPECT_EQ(*ok, "ok");
}

TEST_P(Read, ASnapshotDoesNotMoveUntilRefreshed) {
  const std::string path = study();
  Store s = open_ok(path);
  ASSERT_TRUE(s.enroll("A"));
  StudyReader r = read_ok(path);
  ASSERT_TRUE(s.enroll("B"));  // the writer goes on while the reader holds its snapshot
  EXPECT_EQ(r.ledger()->size(), 1u);
  ASSERT_TRUE(r.refresh());
  EXPECT_EQ(r.ledger()->size(), 2u);
  // The Store's own reader sees its writes at once.
  EXPECT_EQ(s.read().ledger()->size(), 2u);
}

TEST(ReadFile, RefusesWhatIsNotADtlabDatabaseWithItsKind) {
  TempDir dir;
  auto missing = StudyReader::open(dir.file("missing.sqlite"));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::not_found);
  EXPECT_FALSE(fs::exists(dir.file("missing.sqlite")));
  const std::string text = dir.file("text.sqlite");
  std::ofstream(text) << std::string(4096, 't');
  auto bad = StudyReader::open(text);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::invalid_input);
  const std::string empty = dir.file("empty.sqlite");
  std::ofstream(empty).close();
  auto e = StudyReader::open(empty);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("not a dtlab study database"), std::string::npos) << e.error().to_string();
}

// Schema v3 on both engines: the displays a session recorded (in the order recorded, NULL rate
// kept), the per-trial warm-up frame, steady median, late frames and refresh rate as frame_stats()
// computed them; bad display values refused by the store with the field, and by the schema itself.
TEST_P(Read, DisplaysAndFrameTimingComeBack) {
  const std::string path = study();
  Store s = open_ok(path);
  auto e = s.enroll("P1");
  const design::Plan plan = make_plan(e->index, e->order_row, 1);
  auto ses = s.begin_session("P1", plan);
  ASSERT_TRUE(ses);
  const DisplayInfo window{"window", 2560, 1440, 59.94, "4.6 / NVIDIA GeForce", "HDMI-1"};
  ASSERT_TRUE(s.record_display(*ses, window));
  ASSERT_TRUE(s.record_display(*ses, DisplayInfo{"headless", 800, 600, std::nullopt, "OSMesa", ""}));
  for (const auto& [bad, field] : std::vector<std::pair<DisplayInfo, std::string>>{
           {{"tv", 800, 600, std::nullopt, "", ""}, "display.kind"},
           {{"window", 0, 600, std::nullopt, "", ""}, "display.size"},
           {{"window", 800, 600, 0.0, "", ""}, "display.refresh_hz"},
           {{"window", 800, 600, std::nan(""), "", ""}, "display.refresh_hz"}}) {
    auto st = s.record_display(*ses, bad);
    ASSERT_FALSE(st) << field;
    EXPECT_EQ(st.error().field, field) << st.error().to_string();
  }
  const TrialRecord paced = make_record(4, plan.trials[0], 6, 59.94), single = make_record(4, plan.trials[1], 1);
  ASSERT_TRUE(s.record_trial(*ses, paced));
  ASSERT_TRUE(s.record_trial(*ses, single));

  StudyReader r = read_ok(path);
  auto sessions = r.sessions();
  ASSERT_TRUE(sessions);
  const auto& d = (*sessions)[0].displays;
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].info.kind, "window");
  EXPECT_EQ(d[0].info.width, 2560);
  EXPECT_EQ(d[0].info.height, 1440);
  EXPECT_EQ(d[0].info.refresh_hz, 59.94);
  EXPECT_EQ(d[0].info.renderer, window.renderer);
  EXPECT_EQ(d[0].info.monitor, "HDMI-1");
  EXPECT_EQ(d[1].info.kind, "headless");
  EXPECT_FALSE(d[1].info.refresh_hz);
  EXPECT_LE(d[0].recorded_at, d[1].recorded_at);
  auto t = r.trials("P1");
  ASSERT_EQ(t->size(), 2u);
  EXPECT_EQ((*t)[0].frames.first_ms, paced.frames.first_ms);
  EXPECT_EQ((*t)[0].frames.steady_median_ms, paced.frames.steady_median_ms);
  EXPECT_EQ((*t)[0].frames.late, paced.frames.late);
  EXPECT_EQ((*t)[0].frames.refresh_hz, 59.94);
  EXPECT_EQ((*t)[1].frames.first_ms, single.frames.first_ms);
  EXPECT_FALSE((*t)[1].frames.steady_median_ms || (*t)[1].frames.late || (*t)[1].frames.refresh_hz);

  // The schema's own guards, past the store: CHECKs and append-only triggers on both engines.
  RawDb db(path);
  const std::string insert = "INSERT INTO session_displays SELECT id, '2024-01-01T00:00:00.000Z', ";
  for (const char* values : {"'tv', 1, 1, NULL", "'window', 0, 1, NULL", "'window', 1, 1, 0", "'window', 1, 1, -60"})
    EXPECT_FALSE(db.exec(insert + values + ", '', '' FROM sessions")) << values;
  EXPECT_TRUE(db.exec(insert + "'window', 1, 1, 60, '', '' FROM sessions")) << db.errmsg();
  EXPECT_FALSE(db.exec("UPDATE session_displays SET width = 2"));
  EXPECT_FALSE(db.exec("DELETE FROM session_displays"));
  EXPECT_EQ(db.count("SELECT count(*) FROM session_displays"), 3);
}

// Regression (issue 12): a schema_migrations row newer than this build with user_version still
// current was refused by the writer but read by export, analyze and plan. One check for all.
TEST_P(Read, ANewerMigrationRowIsRefusedByReaderAndWriterAlike) {
  const std::string path = study();
  { Store s = open_ok(path); }
  {
    RawDb db(path);
    ASSERT_TRUE(db.exec("INSERT INTO schema_migrations VALUES (999, 'from the future', '2030-01-01T00:00:00.000Z', "
                        "'dtlab 9')"))
        << db.errmsg();
  }
  auto r = StudyReader::open(path);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("schema version 999"), std::string::npos) << r.error().to_string();
  auto w = Store::open(path, study_info());
  ASSERT_FALSE(w);
  EXPECT_NE(w.error().message.find("schema version 999"), std::string::npos) << w.error().to_string();
}

// Runs `body` in a child process as an unprivileged user (nobody), so file permissions bind
// even when the tests run as root; returns the child's exit status.
template <class F>
int as_nobody(F&& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::getuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(90);
    ::_exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Regression (issue 12): reading on read-only media failed ("attempt to write a readonly
// database"), and a read-only file in a writable directory left -wal/-shm behind.
TEST(ReadFile, WorksOnReadOnlyMediaAndLeavesNothingBehind) {
  TempDir dir;
  const fs::path media = fs::path(dir.file("archive"));
  fs::create_directories(media);
  const std::string path = (media / "study.sqlite").string();
  write_study(path);
  ::chmod(media.c_str(), 0755);  // owned by root: nobody cannot write the directory ...
  ::chmod(path.c_str(), 0644);   // ... nor the file
  ::chmod(dir.file("").c_str(), 0755);
  const int rc = as_nobody([&] {
    auto r = StudyReader::open(path);
    if (!r) {
      std::fprintf(stderr, "%s\n", r.error().to_string().c_str());
      return 1;
    }
    auto t = r->trials();
    if (!t || t->size() != 4) return 2;
    auto ok = r->integrity_check();
    return ok && *ok == "ok" ? 0 : 3;
  });
  if (rc == 90) GTEST_SKIP() << "cannot drop privileges to nobody here";
  EXPECT_EQ(rc, 0);
  EXPECT_FALSE(fs::exists(path + "-wal"));
  EXPECT_FALSE(fs::exists(path + "-shm"));

  // A write-protected file in a writable directory: read, nothing left beside it.
  const fs::path open_dir = fs::path(dir.file("open"));
  fs::create_directories(open_dir);
  ::chmod(open_dir.c_str(), 0777);
  const std::string copy = (open_dir / "study.sqlite").string();
  fs::copy_file(path, copy);
  ::chmod(copy.c_str(), 0444);
  EXPECT_EQ(as_nobody([&] {
              auto r = StudyReader::open(copy);
              return r && r->ledger() && r->ledger()->size() == 2 ? 0 : 1;
            }),
            0);
  EXPECT_FALSE(fs::exists(copy + "-wal"));
  EXPECT_FALSE(fs::exists(copy + "-shm"));
}


// A write refused for permissions is refused before SQLite touches anything (regression: the
// connection created -wal and -shm beside the read-only file, then failed at its first write).
TEST(StoreFile, ARefusedWriteOnAReadOnlyFileLeavesNothingBehind) {
  TempDir dir;
  const fs::path open_dir = fs::path(dir.file("open"));
  fs::create_directories(open_dir);
  ::chmod(dir.file("").c_str(), 0755);
  ::chmod(open_dir.c_str(), 0777);
  const std::string path = (open_dir / "study.sqlite").string();
  write_study(path);
  ::chmod(path.c_str(), 0444);
  const int rc = as_nobody([&] {
    auto s = Store::open_existing(path);
    if (s) return 1;
    if (s.error().kind != ErrorKind::environment) return 2;
    return s.error().message.find("read-only") != std::string::npos ? 0 : 3;
  });
  if (rc == 90) GTEST_SKIP() << "cannot drop privileges to nobody here";
  EXPECT_EQ(rc, 0);
  EXPECT_FALSE(fs::exists(path + "-wal"));
  EXPECT_FALSE(fs::exists(path + "-shm"));
}

// Damage of every kind is invalid input (exit 1 in every command), found when the file is opened.
TEST(StoreFile, TruncatedFilesAndDirectoriesAreInvalidInputForReaderAndWriter) {
  TempDir dir;
  const std::string good = dir.file("good.sqlite");
  write_study(good);
  auto read_bytes = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string bytes = read_bytes(good);
  const std::string truncated = dir.file("truncated.sqlite");
  { std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 3); }
  const std::string directory = dir.file("folder.sqlite");
  fs::create_directories(directory);
  for (const std::string& path : {truncated, directory}) {
    const std::string before = fs::is_directory(path) ? "" : read_bytes(path);
    auto r = StudyReader::open(path);
    ASSERT_FALSE(r) << path;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_input) << r.error().to_string();
    auto w = Store::open_existing(path);
    ASSERT_FALSE(w) << path;
    EXPECT_EQ(w.error().kind, ErrorKind::invalid_input) << w.error().to_string();
    auto c = Store::open(path, study_info());
    ASSERT_FALSE(c) << path;
    EXPECT_EQ(c.error().kind, ErrorKind::invalid_input) << c.error().to_string();
    if (!fs::is_directory(path)) {
      EXPECT_EQ(read_bytes(path), before);
    }
  }
}

// A table missing from a database is found by every opener (regression: commands ran until the
// first query needed it; `dtlab simulate` left a session running when that came after it began).
TEST_P(Read, AMissingTableIsFoundWhenTheDatabaseIsOpened) {
  const std::string path = study();
  write_study(path);
  { RawDb db(path); ASSERT_TRUE(db.exec("DROP TABLE notes")) << db.errmsg(); }
  auto r = StudyReader::open(path);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_input);
  EXPECT_NE(r.error().message.find("lacks the table(s) notes"), std::string::npos) << r.error().to_string();
  const auto sessions = [&] {
    RawDb db(path);
    return std::to_string(db.count("SELECT count(*) FROM sessions")) + " sessions, " +
           std::to_string(db.count("SELECT count(*) FROM sessions WHERE status = 'running'")) + " running, " +
           std::to_string(db.count("SELECT count(*) FROM studies")) + " studies";
  };
  const std::string before = sessions();
  auto w = Store::open(path, study_info());
  ASSERT_FALSE(w);
  EXPECT_EQ(w.error().kind, ErrorKind::invalid_input);
  EXPECT_EQ(sessions(), before) << "nothing was written";
}

}  // namespace
}  // namespace dtlab::store
