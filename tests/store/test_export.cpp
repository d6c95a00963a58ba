// `dtlab export` and store::export_trials_csv: the header is exactly the one
// documented in README.md and docs/store.md, there is one row per recorded
// trial (participants who withdrew left out, and counted), the demographics
// each participant gave in one column per field, fields follow RFC 4180 with
// NA for missing values, and the command line reports bad input with a
// non-zero exit, on both engines. The CSV is read back with an independent
// RFC 4180 reader written here (and Python's csv module if /usr/bin/python3
// exists).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/store/export.h"
#include "tests/store/store_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

// The documented header for a study with factors transparency, scenario, whose participants were
// enrolled with the demographic fields age and gender (P1), then age and hand (P,2).
const char* kHeader =
    "participant,enrollment_index,session,session_status,order_row,position,block,transparency,scenario,task,trial,"
    "practice,method,trial_seed,scene_hash,answer_count,answer_letter,answer_x,answer_z,truth_count,truth_letter,"
    "truth_x,truth_z,rel_error,signed_error,correct,distance,completion_time_s,started_at,ended_at,frame_count,"
    "frame_ms_mean,frame_ms_sd,frame_ms_p95,frame_ms_max,frame_first_ms,frame_ms_median,late_frames,refresh_hz,"
    "protocol_sha256,design_revision,excluded,demo_age,demo_gender,demo_hand";

// Minimal RFC 4180 reader: records of fields, quoted fields may hold , " CR LF.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> out(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') out.back().back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back().back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.back().emplace_back();
    } else if (c == '\n') {
      out.emplace_back(1);
    } else {
      out.back().back() += c;
    }
  }
  if (out.back().size() == 1 && out.back()[0].empty()) out.pop_back();
  return out;
}

// A study: P1 finishes 4 trials (the T3 at position 3 unanswered), "P,2 \"x\"" records 2
// and is released; P3 is enrolled without a session. P1 and P,2 give demographics (P,2 a field
// P1 lacks, and a value CSV quotes); P3 none.
std::string make_db(const std::string& path, int* recorded) {
  auto s = Store::open(path, study_info());
  EXPECT_TRUE(s);
  *recorded = 0;
  for (const std::string id : {"P1", "P,2 \"x\""}) {
    auto e = id == "P1" ? s->enroll(id, {{"age", "27"}, {"gender", "f"}})
                        : s->enroll(id, {{"age", "35"}, {"hand", "left, \"mostly\""}});
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s->begin_session(id, plan);
    const int n = id == "P1" ? 4 : 2;
    for (int i = 0; i < n; ++i) {
      TrialRecord r = make_record(5, plan.trials[static_cast<std::size_t>(i)], 30);
      if (id == "P1" && i == 2) r.answer.reset();  // position 3 is a T3
      EXPECT_TRUE(s->record_trial(*ses, r));
      ++*recorded;
    }
    if (id == "P1") {
      EXPECT_TRUE(s->finish_session(*ses));
    }
  }
  EXPECT_TRUE(s->release("P,2 \"x\""));
  EXPECT_TRUE(s->enroll("P3"));
  return path;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Export : public OnBothBackends {};
class ExportCommand : public OnBothBackends {};
DTLAB_ON_BOTH_BACKENDS(Export);
DTLAB_ON_BOTH_BACKENDS(ExportCommand);

TEST_P(Export, HeaderIsAsDocumentedAndOneRowPerRecordedTrial) {
  int recorded = 0;
  const std::string path = make_db(study(), &recorded);
  std::ostringstream out;
  auto sum = export_trials_csv(path, out);
  ASSERT_TRUE(sum) << sum.error().to_string();
  const std::string text = out.str();
  EXPECT_EQ(text.substr(0, text.find('\n')), kHeader);
  EXPECT_EQ(sum->rows, recorded);
  const auto rows = parse_csv(text);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(recorded + 1));
  const auto& h = rows[0];
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(h.begin(), h.end(), name) - h.begin());
  };
  for (const auto& r : rows) ASSERT_EQ(r.size(), h.size());
  // Ordered by enrollment index, then position; values as stored.
  const design::Plan plan = make_plan(0, 0, 1);
  EXPECT_EQ(rows[1][col("participant")], "P1");
  EXPECT_EQ(rows[1][col("position")], "1");
  EXPECT_EQ(rows[1][col("trial_seed")], std::to_string(plan.trials[0].seed));  // all 64 bits
  EXPECT_EQ(rows[1][col("transparency")], "off");
  EXPECT_EQ(rows[1][col("scenario")], "ABSTRACT");
  EXPECT_EQ(rows[1][col("session_status")], "finished");
  EXPECT_EQ(rows[1][col("answer_letter")], "NA");  // T1 has a count, no letter
  const TrialRecord r1 = make_record(5, plan.trials[0], 30);
  EXPECT_EQ(std::stod(rows[1][col("completion_time_s")]), r1.completion_s);  // shortest round-trip form
  EXPECT_EQ(rows[1][col("started_at")], "2023-11-14T22:15:00.000Z");          // 1700000000000 + 100000 ms
  EXPECT_EQ(rows[3][col("task")], "T3");
  EXPECT_EQ(rows[3][col("answer_x")], "NA");  // the unanswered T3 ...
  EXPECT_NE(rows[3][col("truth_x")], "NA");   // ... keeps its truth
  EXPECT_EQ(rows[3][col("distance")], "NA");
  EXPECT_EQ(rows[5][col("participant")], "P,2 \"x\"");  // quoted and read back intact
  EXPECT_EQ(rows[5][col("session_status")], "abandoned");
  EXPECT_NE(text.find("\"P,2 \"\"x\"\"\""), std::string::npos);
  // Demographics: one column per field, NA where the participant has none.
  EXPECT_EQ(rows[1][col("demo_age")], "27");
  EXPECT_EQ(rows[1][col("demo_gender")], "f");
  EXPECT_EQ(rows[1][col("demo_hand")], "NA");
  EXPECT_EQ(rows[5][col("demo_gender")], "NA");
  EXPECT_EQ(rows[5][col("demo_hand")], "left, \"mostly\"");
}

// A participant who withdrew their consent is left out of the export (and trial_table), with the
// count in the summary; their demographic fields still name columns. A factor named like a
// demographic column is refused at open, so the two never clash.
TEST_P(Export, LeavesWithdrawnParticipantsOutAndCountsThem) {
  int recorded = 0;
  const std::string path = make_db(study(), &recorded);
  {
    auto s = Store::open(path, study_info());
    ASSERT_TRUE(s);
    auto e = s->enroll("W", {{"age", "50"}, {"glasses", "yes"}});
    const design::Plan plan = make_plan(e->index, e->order_row, 1);
    auto ses = s->begin_session("W", plan);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(s->record_trial(*ses, make_record(5, plan.trials[i], 30)));
    ASSERT_TRUE(s->withdraw("W", "withdrew consent", "RA"));
    ASSERT_TRUE(s->withdraw("P1", "withdrew consent", "RA"));
  }
  std::ostringstream out;
  auto sum = export_trials_csv(path, out);
  ASSERT_TRUE(sum) << sum.error().to_string();
  EXPECT_EQ(sum->rows, 2);               // P,2's two trials
  EXPECT_EQ(sum->withdrawn, 2);          // P1 and W
  EXPECT_EQ(sum->withdrawn_rows, 4 + 3);
  const auto rows = parse_csv(out.str());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].back(), "demo_glasses");
  EXPECT_EQ(rows[1][0], "P,2 \"x\"");
  RawDb db(path);
  EXPECT_EQ(db.count("SELECT count(*) FROM trial_table"), 2);
  EXPECT_EQ(db.columns("SELECT * FROM trial_table"), rows[0]);

  StudyInfo bad = study_info();
  bad.factors = {"transparency", "Demo_age"};
  auto refused = Store::open(study("other"), bad);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().field, "study.factors");
  EXPECT_NE(refused.error().message.find("demographic columns"), std::string::npos) << refused.error().to_string();
}

TEST(ExportFile, ErrorsNameTheFileAndNeverCreateOne) {
  TempDir dir;
  std::ostringstream out;
  const std::string missing = dir.file("missing.sqlite");
  auto a = export_trials_csv(missing, out);
  ASSERT_FALSE(a);
  EXPECT_EQ(a.error().file, missing);
  EXPECT_EQ(a.error().kind, ErrorKind::not_found);
  EXPECT_FALSE(std::filesystem::exists(missing));
  const std::string text = dir.file("text.sqlite");
  std::ofstream(text) << "hello, world\n" << std::string(100, 'z');
  auto b = export_trials_csv(text, out);
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("not an SQLite database"), std::string::npos) << b.error().to_string();
}

TEST_P(ExportCommand, WritesTheFileAndReportsBadInput) {
  TempDir& dir = dir_;
  int recorded = 0;
  const std::string db = make_db(study(), &recorded);
  const std::string csv = dir.file("trials.csv");
  const std::string err = dir.file("err.txt");
  const std::string bin = DTLAB_BINARY;
  ASSERT_EQ(std::system((bin + " export '" + db + "' --csv '" + csv + "' 2>'" + err + "'").c_str()), 0) << slurp(err);
  std::ostringstream lib;
  ASSERT_TRUE(export_trials_csv(db, lib));
  EXPECT_EQ(slurp(csv), lib.str());

  const std::string junk = dir.file("junk.sqlite");
  std::ofstream(junk) << std::string(4096, 'j');
  const int rc = std::system((bin + " export '" + junk + "' --csv '" + dir.file("x.csv") + "' 2>'" + err + "'").c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 1) << rc;
  EXPECT_NE(slurp(err).find(junk), std::string::npos) << slurp(err);
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.csv")));  // no half-written output
  const int usage = std::system((bin + " export '" + db + "' 2>/dev/null").c_str());
  EXPECT_TRUE(WIFEXITED(usage) && WEXITSTATUS(usage) == 2);  // --csv is required
}

// The view SQLite clients read (trial_table) and the export come from two independent paths
// (SQL in the schema, the typed reader + CSV writer here): they must agree cell for cell,
// including the design revision and the excluded column, after revisions and decisions.
TEST_P(Export, EqualsTheTrialTableViewCellForCell) {
  int recorded = 0;
  const std::string path = make_db(study(), &recorded);
  {
    StudyInfo reworded = study_info("id = \"test2x2\"\n# protocol text, reworded\n");
    reworded.design_sha256 = std::string(64, 'a');
    OpenOptions o;
    o.design_hash_of = [](const std::string&) { return std::optional<std::string>(std::string(64, 'a')); };
    auto s = Store::open(path, reworded, o);  // same design, new text: a revision without any flag
    ASSERT_TRUE(s) << s.error().to_string();
    ASSERT_TRUE(s->exclude("P1", std::nullopt, "misunderstood, \"the\" task", "RA"));
    ASSERT_TRUE(s->exclude("P,2 \"x\"", 2, "fire alarm", "RA"));
    ASSERT_TRUE(s->include("P1", std::nullopt, "", "PI"));
    ASSERT_TRUE(s->exclude("P1", 3, "looked away", ""));
    auto e = s->enroll("W", {{"age", "61"}, {"visor", "on"}});  // withdraws: left out of both
    auto ses = s->begin_session("W", make_plan(e->index, e->order_row, 1));
    ASSERT_TRUE(s->record_trial(*ses, make_record(5, **s->next_trial(*ses), 30)));
    ASSERT_TRUE(s->withdraw("W", "withdrew consent", "RA"));
  }
  std::ostringstream out;
  auto sum = export_trials_csv(path, out);
  ASSERT_TRUE(sum) << sum.error().to_string();
  EXPECT_EQ(sum->excluded, 2);
  const auto exported = parse_csv(out.str());
  RawDb db(path);
  const auto view = db.rows("SELECT * FROM trial_table ORDER BY enrollment_index, position");
  ASSERT_EQ(exported.size(), view.size() + 1);
  const std::vector<std::string> header = db.columns("SELECT * FROM trial_table");
  EXPECT_EQ(exported[0], header);
  for (std::size_t i = 0; i < view.size(); ++i)
    for (std::size_t c = 0; c < header.size(); ++c) {
      std::string v = view[i][c];
      if (v == "NULL") v = "NA";
      const std::string& e = exported[i + 1][c];
      if (v != e && v.find_first_not_of("0123456789.-e+") == std::string::npos && !v.empty())
        EXPECT_EQ(std::stod(v), std::stod(e)) << header[c] << " of row " << i + 1;  // same double, other spelling
      else
        EXPECT_EQ(v, e) << header[c] << " of row " << i + 1;
    }
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  EXPECT_EQ(exported[1][col("excluded")], "NA");  // P1 excluded, then included again
  EXPECT_EQ(exported[3][col("excluded")], "looked away");
  EXPECT_EQ(exported[6][col("excluded")], "fire alarm");
  EXPECT_EQ(exported[1][col("design_revision")], "1");  // the old text hashed by the caller's function
  EXPECT_EQ(exported[1][col("demo_age")], "27");
  EXPECT_EQ(exported[6][col("demo_hand")], "left, \"mostly\"");
  EXPECT_EQ(header.back(), "demo_visor");  // W's field names a column, W's rows are left out
  EXPECT_EQ(view.size(), 6u);
}

// Optional: an independent CSV reader (Python's csv module) agrees on shape.
TEST(ExportFile, PythonCsvModuleReadsItAsIs) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  TempDir dir;
  int recorded = 0;
  const std::string db = make_db(dir.file("study.sqlite"), &recorded);
  const std::string csv = dir.file("trials.csv");
  std::ofstream out(csv);
  ASSERT_TRUE(export_trials_csv(db, out));
  out.close();
  const std::string script =
      "import csv,sys; r=list(csv.DictReader(open(sys.argv[1], newline=''))); "
      "assert len(r)==" + std::to_string(recorded) + ", len(r); "
      "assert r[4]['participant']=='P,2 \"x\"', r[4]['participant']; "
      "assert all(len(x)==45 for x in r); assert r[4]['demo_hand']=='left, \"mostly\"', r[4]; "
      "float(r[0]['completion_time_s'])";
  const std::string cmd = "/usr/bin/python3 -c '" + [&] {
    std::string q;
    for (char c : script) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q;
  }() + "' '" + csv + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}

}  // namespace
}  // namespace dtlab::store
