// sim::simulate_study (study/sim/simulate.h), the library side of `dtlab
// simulate` and `dtlab demo`: a protocol its sessions would refuse opens
// nothing; a run enrolls, records every planned trial and reports it through
// the caller's callbacks; a second run finds the session finished and runs
// nothing. The command line's behaviour (messages, exit codes, Ctrl-C) is
// tests/sim/test_simulate_cli.cpp's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "app/platform/gl_context.h"
#include "study/sim/simulate.h"

namespace dtlab::sim {
namespace {

protocol::Protocol pilot() {
  auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().to_string());
  return p.value();
}

std::string fresh_db(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab-simulate-study-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  return path.string();
}

StudyRun headless(const std::string& db) {
  StudyRun run;
  run.db = db;
  run.participants = 1;
  run.make_context = [](int w, int h) -> Result<std::shared_ptr<void>> {
    auto ctx = platform::create_headless(w, h, 0);
    if (!ctx) return ctx.error();
    return std::shared_ptr<void>(std::move(ctx.value()));
  };
  return run;
}

TEST(SimulateStudy, AProtocolItsSessionsWouldRefuseOpensNothing) {
  protocol::Protocol p = pilot();
  p.scenarios.front().tasks.front().scene.object_radius.max = 1000;  // larger than the cube
  StudyRun run = headless(fresh_db("refused.sqlite"));
  std::vector<Diagnostic> seen;
  bool enrolled = false;
  run.on_checked = [&](const std::vector<Diagnostic>& d) { seen = d; };
  run.on_roster = [&](const Roster&, long long) { enrolled = true; };
  const StudyResult r = simulate_study(p, run);
  EXPECT_TRUE(r.protocol_invalid);
  EXPECT_TRUE(protocol::has_errors(r.diagnostics));
  EXPECT_EQ(seen.size(), r.diagnostics.size());
  EXPECT_FALSE(enrolled);
  EXPECT_FALSE(r.enroll_error || r.run_error);
  EXPECT_EQ(r.trials_run, 0);
  EXPECT_FALSE(std::filesystem::exists(run.db));
}

TEST(SimulateStudy, RunsEveryPlannedTrialThenFindsTheSessionFinished) {
  const protocol::Protocol p = pilot();
  StudyRun run = headless(fresh_db("pilot.sqlite"));
  long long planned = -1;
  std::size_t to_run = 99;
  int trials = 0, finished = 0;
  run.on_roster = [&](const Roster& r, long long n) {
    planned = n;
    to_run = r.to_run.size();
  };
  run.on_progress = [&](const Progress& pr) {
    trials += pr.kind == Progress::Kind::trial;
    finished += pr.kind == Progress::Kind::finished;
  };
  const StudyResult first = simulate_study(p, run);
  ASSERT_FALSE(first.protocol_invalid || first.enroll_error || first.run_error);
  EXPECT_FALSE(protocol::has_errors(first.diagnostics));
  EXPECT_EQ(to_run, 1u);
  EXPECT_EQ(planned, 8);  // pilot.toml: 4 conditions x 2 tasks x 1 trial
  EXPECT_EQ(trials, 8);
  EXPECT_EQ(finished, 1);
  EXPECT_EQ(first.trials_run, 8);
  EXPECT_EQ(first.finished_total, 1);
  EXPECT_EQ(first.already_finished, 0);
  EXPECT_EQ(first.failed, 0);
  EXPECT_FALSE(first.stopped);

  trials = 0;
  const StudyResult again = simulate_study(p, run);
  ASSERT_FALSE(again.protocol_invalid || again.enroll_error || again.run_error);
  EXPECT_EQ(to_run, 0u);
  EXPECT_EQ(planned, 0);
  EXPECT_EQ(trials, 0);
  EXPECT_EQ(again.trials_run, 0);
  EXPECT_EQ(again.already_finished, 1);
  EXPECT_EQ(again.finished_total, 1);
  std::filesystem::remove_all(std::filesystem::path(run.db).parent_path());
}

}  // namespace
}  // namespace dtlab::sim
