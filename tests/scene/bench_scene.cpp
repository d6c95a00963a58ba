// Generation time per scene kind and task (aim: a WALKTHROUGH scene in under
// 50 ms), scenes per second, and the time of hashing alone for comparison.
// Prints; never asserts.
#include <benchmark/benchmark.h>

#include "study/scene/generate.h"
#include "study/scene/hash.h"

namespace {

using namespace dtlab::scene;

void BM_Generate(benchmark::State& state, Kind kind, Task task) {
  std::uint64_t seed = 0;
  std::size_t triangles = 0;
  for (auto _ : state) {
    auto scene = generate(kind, task, ++seed);
    if (!scene.ok()) {
      state.SkipWithError(scene.error().to_string().c_str());
      return;
    }
    triangles = 0;
    for (const auto& o : scene->objects) triangles += scene->meshes[o.mesh].triangle_count();
    benchmark::DoNotOptimize(scene->hash);
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.SetItemsProcessed(state.iterations());  // scenes per second
}

void BM_Hash(benchmark::State& state, Kind kind, Task task) {
  const auto scene = generate(kind, task, 1);
  for (auto _ : state) benchmark::DoNotOptimize(scene_hash(*scene));
}

BENCHMARK_CAPTURE(BM_Generate, abstract_T1, Kind::abstract, Task::T1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Generate, abstract_T2, Kind::abstract, Task::T2)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Generate, walkthrough_T3, Kind::walkthrough, Task::T3)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Generate, walkthrough_T4, Kind::walkthrough, Task::T4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Hash, abstract_T1, Kind::abstract, Task::T1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Hash, walkthrough_T3, Kind::walkthrough, Task::T3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
