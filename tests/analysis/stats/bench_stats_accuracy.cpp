// What exact-offset accuracy costs. The exact method parses every number from
// its decimal text, subtracts a reference value exactly on the digits and
// sums squares of the rounded differences with compensation; the plain method
// is strtod plus the textbook two-pass sums in double. Measured on NIST StRD
// SmLs09 (18009 values with 13 constant leading digits) and on a synthetic
// 10^6-value file of the same kind; prints time ratios and the LRE each
// method reaches, all from one run. Never asserts.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/csv.h"
#include "analysis/stats/long_data.h"

namespace {

using namespace dtlab::stats;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// NIST SmLs09 as CSV text.
const std::string& smls09() {
  static const std::string text = read_file(std::string(DTLAB_SOURCE_DIR) + "/tests/analysis/data/nist/SmLs09.csv");
  return text;
}

constexpr int kBigGroups = 10, kBigPerGroup = 100000;
const std::string& big() {  // group g: 1000000000000.(5+g) +- 0.1, SS_within = 0.01 per value
  static const std::string text = [] {
    std::string s = "treatment,response\n";
    s.reserve(30u * kBigGroups * kBigPerGroup);
    for (int g = 0; g < kBigGroups; ++g)
      for (int i = 0; i < kBigPerGroup; ++i) {
        const int tenths = 5 + g + (i % 2 == 0 ? 1 : -1);
        char line[64];
        std::snprintf(line, sizeof line, "%d,%lld.%d\n", g, 1000000000000LL + tenths / 10, tenths % 10);
        s += line;
      }
    return s;
  }();
  return text;
}
const double kBigSsWithin = kBigGroups * kBigPerGroup * 0.01;
const double kSmLs09SsWithin = 1.8e2;  // NIST certified

double lre(double x, double c) { return x == c ? 15.0 : std::min(15.0, -std::log10(std::fabs(x - c) / std::fabs(c))); }

// Plain method: strtod on the text, two-pass sums in double.
double plain_ss_within(const CsvTable& t) {
  std::map<std::string, std::vector<double>> groups;
  for (const auto& r : t.rows) groups[r[0]].push_back(std::strtod(r[1].c_str(), nullptr));
  double ssw = 0.0;
  for (const auto& [g, v] : groups) {
    double m = 0.0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) ssw += (x - m) * (x - m);
  }
  return ssw;
}

double exact_ss_within(const CsvTable& t) {
  auto d = long_data_from_csv(t, {"response", "", {}, {"treatment"}});
  return one_way_anova(*d).value().effect.ss_error;
}

void run(benchmark::State& state, const std::string& text, bool exact, double certified) {
  const CsvTable table = *parse_csv(text, "bench.csv");
  double ssw = 0.0;
  for (auto _ : state) {
    ssw = exact ? exact_ss_within(table) : plain_ss_within(table);
    benchmark::DoNotOptimize(ssw);
  }
  state.counters["LRE"] = lre(ssw, certified);
  state.counters["values/s"] = benchmark::Counter(static_cast<double>(table.rows.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_SmLs09_plain(benchmark::State& s) { run(s, smls09(), false, kSmLs09SsWithin); }
void BM_SmLs09_exact(benchmark::State& s) { run(s, smls09(), true, kSmLs09SsWithin); }
void BM_Big_plain(benchmark::State& s) { run(s, big(), false, kBigSsWithin); }
void BM_Big_exact(benchmark::State& s) { run(s, big(), true, kBigSsWithin); }
BENCHMARK(BM_SmLs09_plain)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SmLs09_exact)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Big_plain)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Big_exact)->Unit(benchmark::kMillisecond)->Iterations(3);

// Records each benchmark's time per iteration so main() can print ratios.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const auto& r : runs) {
      times[r.benchmark_name()] = r.GetAdjustedRealTime();
      lres[r.benchmark_name()] = r.counters.count("LRE") ? static_cast<double>(r.counters.at("LRE")) : NAN;
    }
  }
  std::map<std::string, double> times, lres;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\ncost of accuracy (exact-offset time / plain two-pass time, same run; time per iteration includes\n"
              "reading the numbers from the CSV cells):\n");
  for (const char* data : {"SmLs09", "Big"}) {
    const std::string p = std::string("BM_") + data + "_plain", e = std::string("BM_") + data + "_exact";
    auto find = [&](const std::string& prefix, std::map<std::string, double>& m) -> double {
      for (auto& [name, v] : m)
        if (name.rfind(prefix, 0) == 0) return v;
      return NAN;
    };
    const double tp = find(p, reporter.times), te = find(e, reporter.times);
    std::printf("  %-7s ratio %.2fx   LRE plain %.1f, exact %.1f\n", data, te / tp, find(p, reporter.lres), find(e, reporter.lres));
  }
  benchmark::Shutdown();
  return 0;
}
