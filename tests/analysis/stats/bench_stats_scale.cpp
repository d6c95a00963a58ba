// How the statistics scale to large tables: 10^6 rows of long CSV text
// (250000 subjects x 4 cells; for anova 4 groups), parsed and tested end to
// end as `dtlab stats` does it, for anova, rm-anova, friedman and wilcoxon
// (250000 subjects x 2 cells). Then the wide cases: rm-anova on one within
// factor with many levels (in memory, the test alone: 3 x 3000, 30 x 3000,
// 1500 x 1000 subjects x levels) and Friedman's exact p at k = 6 (n = 9, the
// most --exact auto enumerates, and n = 12 with --exact always). Prints
// seconds per case; the README/docs budget is under 10 s each on 2 cores.
// Not run by ctest (benchmarks do not assert).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

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

// rm-anova alone on `subjects` x `levels` cells of one within factor.
void BM_RmAnovaManyLevels(benchmark::State& state) {
  const auto subjects = static_cast<std::size_t>(state.range(0)), levels = static_cast<std::size_t>(state.range(1));
  LongData d;
  d.within.push_back({"cond", {}});
  std::vector<double> y;
  for (std::size_t s = 0; s < subjects; ++s)
    for (std::size_t c = 0; c < levels; ++c) {
      d.subject.push_back("s" + std::to_string(s));
      d.within[0].level.push_back("c" + std::to_string(c));
      y.push_back(static_cast<double>((s * 7919 + c * 104729) % 1000) / 10);
    }
  d.dv = Measurements::from_doubles(y);
  for (auto _ : state) benchmark::DoNotOptimize(rm_anova(d).ok());
}

// Friedman's exact p for n untied blocks of k = 6 (p near .15).
void BM_FriedmanExactK6(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<std::vector<double>> y;
  for (int i = 0; i < n; ++i) {
    std::vector<double> row;
    for (int j = 0; j < 6; ++j) row.push_back(static_cast<double>((i * 7 + j * (i % 5 + 1)) % 6) + 0.1 * j);
    y.push_back(row);
  }
  ExactOptions always;
  always.mode = ExactMode::always;
  for (auto _ : state) benchmark::DoNotOptimize(friedman_blocks(y, always).p_exact);
}

BENCHMARK(BM_ParseOnly)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Anova)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_RmAnova)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Friedman)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Wilcoxon)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_RmAnovaManyLevels)->Args({3, 3000})->Args({30, 3000})->Args({1500, 1000})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_FriedmanExactK6)->Arg(9)->Arg(12)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
