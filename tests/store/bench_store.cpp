// The study database on both engines, in one run: trials recorded per second
// (one finished trial = one commit with its result, events and camera poses;
// with 0, 600 and 3600 poses: nothing, 10 s and 60 s at 60 fps) and the
// latency of one enrollment, on SQLite (a file, synchronous = FULL) and on a
// PostgreSQL server on this machine (a throwaway one, started by
// tests/store/pg_server.sh with fsync on, synchronous_commit on, Unix
// socket). Prints the PostgreSQL / SQLite ratio of every pair. Never asserts.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "tests/store/study_fixtures.h"

namespace {

using namespace dtlab::store;
using namespace dtlab::store::testing;
namespace fs = std::filesystem;

const fs::path& scratch() {
  static const fs::path dir = fs::temp_directory_path() / ("dtlab-bench-store-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// The server's base URI, or "" (then the PostgreSQL half is skipped with the reason in `why`).
std::string server(std::string* why) {
  static std::string uri, reason;
  static bool started = false;
  if (!started) {
    started = true;
    const std::string state = (scratch() / "pg").string();
    const std::string script = std::string(DTLAB_SOURCE_DIR) + "/tests/store/pg_server.sh";
    if (std::system(("'" + script + "' start '" + state + "' durable").c_str()) != 0) reason = "pg_server.sh failed";
    std::ifstream in(state + "/status");
    std::string word;
    in >> word;
    std::getline(in, word == "uri" ? uri : reason);
    uri.erase(0, uri.find_first_not_of(' '));
  }
  if (why) *why = reason;
  return uri;
}

std::string new_study(bool pg) {
  static int n = 0;
  ++n;
  if (!pg) return (scratch() / ("s" + std::to_string(n) + ".sqlite")).string();
  return server(nullptr) + "&schema=b" + std::to_string(::getpid()) + "_" + std::to_string(n);
}

bool skip_without_server(benchmark::State& state, bool pg) {
  std::string why;
  if (pg && server(&why).empty()) {
    state.SkipWithError(("no PostgreSQL server: " + why).c_str());
    return true;
  }
  return false;
}

// One finished trial per iteration, each its own commit: result, scores, 20 events, `frames` poses.
void BM_RecordTrial(benchmark::State& state, bool pg) {
  if (skip_without_server(state, pg)) return;
  const int frames = static_cast<int>(state.range(0));
  auto s = Store::open(new_study(pg), study_info());
  if (!s) return state.SkipWithError(s.error().to_string().c_str());
  auto e = s->enroll("P1");
  const dtlab::design::Plan plan = make_plan(e->index, e->order_row, static_cast<int>(state.max_iterations / 4 + 1));
  auto ses = s->begin_session("P1", plan);
  if (!ses) return state.SkipWithError(ses.error().to_string().c_str());
  std::size_t next = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const TrialRecord r = make_record(1, plan.trials[next++], frames);
    state.ResumeTiming();
    if (auto st = s->record_trial(*ses, r); !st) return state.SkipWithError(st.error().to_string().c_str());
  }
  state.SetItemsProcessed(state.iterations());  // trials per second
}

// One new participant per iteration: the read-decide-write of the ledger under the write lock.
void BM_Enroll(benchmark::State& state, bool pg) {
  if (skip_without_server(state, pg)) return;
  auto s = Store::open(new_study(pg), study_info());
  if (!s) return state.SkipWithError(s.error().to_string().c_str());
  int n = 0;
  for (auto _ : state)
    if (auto e = s->enroll("P" + std::to_string(n++)); !e) return state.SkipWithError(e.error().to_string().c_str());
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_CAPTURE(BM_RecordTrial, sqlite, false)->Arg(0)->Arg(600)->Arg(3600)->Iterations(200)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecordTrial, pg, true)->Arg(0)->Arg(600)->Arg(3600)->Iterations(200)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Enroll, sqlite, false)->Iterations(300)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Enroll, pg, true)->Iterations(300)->UseRealTime()->Unit(benchmark::kMicrosecond);

// Console output as usual, plus the time of every run, for the ratios.
class Ratios : public benchmark::ConsoleReporter {
 public:
  Ratios() : ConsoleReporter(::isatty(STDOUT_FILENO) ? OO_ColorTabular : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs)
      if (!r.error_occurred) seconds_[r.benchmark_name()] = r.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
    ConsoleReporter::ReportRuns(runs);
  }
  void print() const {
    std::printf("\n%-44s %12s %12s %9s\n", "per operation (one commit)", "SQLite", "PostgreSQL", "PG/SQLite");
    for (const auto& [name, sqlite] : seconds_) {
      const auto at = name.find("/sqlite");
      if (at == std::string::npos) continue;
      const std::string pg_name = name.substr(0, at) + "/pg" + name.substr(at + 7);
      const auto pg = seconds_.find(pg_name);
      if (pg == seconds_.end()) continue;
      std::printf("%-44s %9.3f ms %9.3f ms %9.2f\n", (name.substr(0, at) + name.substr(at + 7)).c_str(), sqlite * 1e3,
                  pg->second * 1e3, pg->second / sqlite);
    }
  }

 private:
  std::map<std::string, double> seconds_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  Ratios reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print();
  std::string why;
  if (!server(&why).empty() || !why.empty())
    std::system(("'" + std::string(DTLAB_SOURCE_DIR) + "/tests/store/pg_server.sh' stop '" + (scratch() / "pg").string() +
                 "' >/dev/null").c_str());
  std::error_code ec;
  fs::remove_all(scratch(), ec);
  return 0;
}
