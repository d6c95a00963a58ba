// How the statistics scale to large tables: 10^6 rows of long CSV text
// (250000 subjects x 4 cells; for anova 4 groups), parsed and tested end to
// end as `dtlab stats` does it, for anova, rm-anova, friedman and wilcoxon
// (250000 subjects x 2 cells). Prints seconds per test; the README/docs
// budget is under 10 s each on 2 cores. Not run by ctest (benchmarks do not assert).
#include <benchmark/benchmark.h>

#include <string>

#include "analysis/stats/anova.h"
#include "analysis/stats/csv.h"
#include "analysis/stats/friedman.h"
#include "analysis/stats/long_data.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/rm_anova.h"

namespace {

using namespace dtlab::stats;

// Long CSV "id,cond,y" with `subjects` x `cells` rows and deterministic values.
std::string table(std::size_t subjects, std::size_t cells) {
  std::string csv = "id,cond,y\n";
  csv.reserve(subjects * cells * 24);
  for (std::size_t s = 0; s < subjects; ++s)
    for (std::size_t c = 0; c < cells; ++c) {
      const std::size_t v = (s * 7919 + c * 104729) % 100003;
      csv += "s" + std::to_string(s) + ",c" + std::to_string(c) + "," + std::to_string(400 + c * 3) + "." +
             std::to_string(v % 1000) + "\n";
    }
  return csv;
}

LongData load(const std::string& csv, bool groups) {
  auto t = parse_csv(csv, "bench.csv");
  ColumnRoles roles{"y", groups ? "" : "id", groups ? std::vector<std::string>{} : std::vector<std::string>{"cond"},
                    groups ? std::vector<std::string>{"cond"} : std::vector<std::string>{}};
  return *long_data_from_csv(*t, roles);
}

void BM_Anova(benchmark::State& state) {
  const std::string csv = table(250000, 4);
  for (auto _ : state) benchmark::DoNotOptimize(one_way_anova(load(csv, true)).ok());
}
void BM_RmAnova(benchmark::State& state) {
  const std::string csv = table(250000, 4);
  for (auto _ : state) benchmark::DoNotOptimize(rm_anova(load(csv, false)).ok());
}
void BM_Friedman(benchmark::State& state) {
  const std::string csv = table(250000, 4);
  for (auto _ : state) benchmark::DoNotOptimize(friedman(load(csv, false)).ok());
}
void BM_Wilcoxon(benchmark::State& state) {
  const std::string csv = table(500000, 2);
  for (auto _ : state) benchmark::DoNotOptimize(paired_tests(load(csv, false)).ok());
}
void BM_ParseOnly(benchmark::State& state) {
  const std::string csv = table(250000, 4);
  for (auto _ : state) benchmark::DoNotOptimize(load(csv, false).rows());
}

BENCHMARK(BM_ParseOnly)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Anova)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_RmAnova)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Friedman)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Wilcoxon)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
