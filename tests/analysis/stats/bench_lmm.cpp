// How the mixed models scale: CSV text of P participants x 200 trials (two
// within factors of 2 levels, 10 items, log-normal times with participant and
// item effects; a 0/1 column beside), parsed and fitted end to end as `dtlab
// stats lmm` does it (CSV, LongData, fit, Satterthwaite tests, one table of
// marginal means). Rows: 100000 (P = 500) and 1000000 (P = 5000); random
// intercepts, by-participant slopes, crossed items, and the binomial GLMM.
// Prints seconds beside the "rows" counter; the aims are 100000 rows
// in under 5 s and 1000000 in under 60 s with random intercepts. Not run by
// ctest (benchmarks do not assert).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "analysis/stats/csv.h"
#include "analysis/stats/emmeans.h"
#include "analysis/stats/lmm.h"
#include "study/common/hash.h"

namespace {

using namespace dtlab::stats;

double uniform(std::uint64_t key) { return static_cast<double>(dtlab::mix64(key) >> 11) * 0x1.0p-53; }
double normal(std::uint64_t key) {  // Box-Muller from two keyed uniforms
  const double u1 = std::max(uniform(key), 1e-300), u2 = uniform(key ^ 0x5bd1e995ULL);
  return std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

std::string table(std::size_t participants) {
  std::string csv = "participant,technique,task,item,time,correct\n";
  csv.reserve(participants * 200 * 48);
  for (std::size_t p = 0; p < participants; ++p) {
    const double u = 0.3 * normal(dtlab::mix64(1, p)), slope = 0.1 * normal(dtlab::mix64(2, p));
    for (std::size_t t = 0; t < 200; ++t) {
      const int a = static_cast<int>(t % 2), b = static_cast<int>((t / 2) % 2);
      const std::uint64_t key = dtlab::mix64(dtlab::mix64(3, p), t);
      const std::size_t item = dtlab::mix64(key, 4) % 10;
      const double w = 0.15 * normal(dtlab::mix64(5, item));
      const double eta = 1 + u + (0.3 + slope) * a - 0.1 * b + w;
      const double time = std::exp(eta + 0.4 * normal(key));
      const int correct = uniform(dtlab::mix64(key, 6)) < 1 / (1 + std::exp(-(1.5 - 0.5 * a + u))) ? 1 : 0;
      csv += "p" + std::to_string(p) + (a ? ",xray" : ",standard") + (b ? ",count" : ",find") + ",i" +
             std::to_string(item) + "," + std::to_string(time) + "," + std::to_string(correct) + "\n";
    }
  }
  return csv;
}

void fit(benchmark::State& state, RandomEffects random, bool item, Family family) {
  const std::size_t participants = static_cast<std::size_t>(state.range(0));
  const std::string csv = table(participants);
  for (auto _ : state) {
    auto t = parse_csv(csv, "bench.csv");
    const bool binomial = family == Family::binomial;
    auto d = lmm_data_from_csv(*t, {binomial ? "correct" : "time", "participant", {"technique", "task"}, {}},
                               item ? "item" : "");
    LmmOptions o;
    o.random = random;
    o.family = family;
    if (!binomial) o.transform = Transform::log;
    auto f = fit_lmm(*d, o);
    if (!f) state.SkipWithError(f.error().to_string().c_str());
    else benchmark::DoNotOptimize(marginal_means(*f, {"technique"}).ok());
  }
  state.counters["rows"] = static_cast<double>(participants * 200);
}

void BM_Intercepts(benchmark::State& s) { fit(s, RandomEffects::intercepts, false, Family::gaussian); }
void BM_Slopes(benchmark::State& s) { fit(s, RandomEffects::slopes, false, Family::gaussian); }
void BM_CrossedItems(benchmark::State& s) { fit(s, RandomEffects::intercepts, true, Family::gaussian); }
void BM_Maximal(benchmark::State& s) { fit(s, RandomEffects::maximal, true, Family::gaussian); }
void BM_Binomial(benchmark::State& s) { fit(s, RandomEffects::intercepts, false, Family::binomial); }

BENCHMARK(BM_Intercepts)->Arg(500)->Arg(5000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Slopes)->Arg(500)->Arg(5000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_CrossedItems)->Arg(500)->Arg(5000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Maximal)->Arg(500)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Binomial)->Arg(500)->Arg(5000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
