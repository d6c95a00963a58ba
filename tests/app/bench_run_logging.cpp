// What logging costs a participant session (issue 10, "Logging"): during a
// frame only in-memory appends happen -- the input events (run::EventLog),
// one camera pose and one frame time -- and the store writes everything when
// the trial ends, in one transaction. This benchmark measures both sides:
// the per-frame cost of the appends (to be read against a 60 Hz frame's
// 16.7 ms) and the end-of-trial commit of a
// trial with N frames and N input events (which happens between trials,
// never during a frame). Prints times; asserts nothing.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "app/run/input.h"
#include "study/common/hash.h"
#include "study/store/store.h"

namespace {

using dtlab::run::Clock;
using dtlab::run::EventLog;
namespace store = dtlab::store;

// One frame of a busy trial: 4 cursor events (a mouse reports at 250 Hz), a pose and a frame time.
void BM_FrameLogging(benchmark::State& state) {
  EventLog log;
  std::vector<store::CameraPose> poses;
  std::vector<double> frame_ms;
  log.start(Clock::now());
  double x = 0;
  for (auto _ : state) {
    for (int i = 0; i < 4; ++i) log.add(store::InputEvent::Kind::cursor, "", x += 1, 300);
    poses.push_back(store::CameraPose{x, 1, 2, 3, 0.5, 0.1});
    frame_ms.push_back(16.6);
    if (poses.size() > 20000) {  // a long trial's worth; start again so memory stays bounded
      poses.clear();
      frame_ms.clear();
      log.take();
      log.start(Clock::now());
    }
  }
}
BENCHMARK(BM_FrameLogging);

// The commit at the end of a trial with `frames` frames and as many input events.
void BM_TrialCommit(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("dtlab_bench_logging_" + std::to_string(::getpid()) + ".sqlite")).string();
  std::filesystem::remove(path);
  store::StudyInfo info;
  info.protocol_id = "bench";
  info.protocol_text = "bench";
  info.protocol_sha256 = dtlab::sha256_hex("bench");
  info.software_version = "bench";
  info.order_rows = 1;
  info.factors = {"f"};
  auto s = store::Store::open(path, info);
  if (!s) {
    state.SkipWithError(s.error().to_string().c_str());
    return;
  }
  store::TrialRecord r;
  r.scene_hash = std::string(64, 'a');
  r.truth = store::Count{5};
  r.answer = store::Count{5};
  std::vector<double> ms(static_cast<std::size_t>(frames), 16.6);
  for (int i = 0; i < frames; ++i) {
    r.poses.push_back(store::CameraPose{i / 60.0, 1, 2, 3, 0.5, 0.1});
    r.events.push_back(store::InputEvent{i / 60.0, store::InputEvent::Kind::cursor, "", 1.0 * i, 300});
  }
  r.frames = store::frame_stats(ms);
  r.completion_s = frames / 60.0;
  int n = 0;
  for (auto _ : state) {
    state.PauseTiming();  // enrolling and beginning the session are not the trial's commit
    const std::string id = "P" + std::to_string(n++);
    auto e = s->enroll(id);
    dtlab::design::Plan plan{"bench", e->index, 0, {}};
    plan.trials.push_back(dtlab::design::PlannedTrial{1, 1, {{"f", "a"}}, "T1", 1, 1, "standard", false});
    auto ses = s->begin_session(id, plan);
    r.position = 1;
    state.ResumeTiming();
    if (auto st = s->record_trial(*ses, r); !st) state.SkipWithError(st.error().to_string().c_str());
  }
  std::filesystem::remove(path);
  std::filesystem::remove(path + "-wal");
  std::filesystem::remove(path + "-shm");
}
BENCHMARK(BM_TrialCommit)->Arg(600)->Arg(3600)->Arg(18000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
