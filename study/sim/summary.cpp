// summarize (summary.h): one pass over the recorded trials.
#include "study/sim/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "study/common/text.h"

namespace dtlab::sim {

namespace {

// The task's accuracy measure of one trial: (name, value), or nullopt when it has none.
std::optional<std::pair<const char*, double>> measure(const store::Scores& s) {
  if (s.rel_error) return std::pair{"rel_error", *s.rel_error};
  if (s.correct) return std::pair{"correct", *s.correct ? 1.0 : 0.0};
  if (s.distance) return std::pair{"distance", *s.distance};
  return std::nullopt;
}

}  // namespace

Result<Summary> summarize(store::StudyReader& reader, const std::string& rendering_factor) {
  auto rows = reader.trials();
  if (!rows) return rows.error();
  struct Acc {
    std::vector<double> times, measure;
    std::string name;
  };
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, Acc> acc;
  std::set<std::string> participants;
  Summary s;
  for (const store::TrialRow& t : *rows) {
    if (t.planned.practice) continue;
    if (t.excluded) {
      ++s.excluded;
      continue;
    }
    const std::pair<std::string, std::string> key{t.planned.task,
                                                  rendering_factor.empty() ? std::string() : t.level(rendering_factor)};
    if (!acc.count(key)) order.push_back(key);
    Acc& a = acc[key];
    a.times.push_back(t.completion_s);
    if (auto m = measure(t.scores)) {
      a.measure.push_back(m->second);
      a.name = m->first;
    }
    participants.insert(t.participant);
    ++s.trials;
  }
  s.participants = static_cast<int>(participants.size());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& key : order) {
    const Acc& a = acc[key];
    SummaryCell c;
    c.task = key.first;
    c.rendering = key.second;
    c.trials = static_cast<int>(a.times.size());
    for (double v : a.times) c.time_mean += v;
    c.time_mean /= static_cast<double>(a.times.size());
    if (a.times.size() > 1) {
      double ss = 0;
      for (double v : a.times) ss += (v - c.time_mean) * (v - c.time_mean);
      c.time_sd = std::sqrt(ss / static_cast<double>(a.times.size() - 1));
    }
    c.measure = a.name;
    c.measured = static_cast<int>(a.measure.size());
    for (double v : a.measure) c.measure_mean += v;
    if (!a.measure.empty()) c.measure_mean /= static_cast<double>(a.measure.size());
    s.cells.push_back(c);
  }
  return s;
}

std::string format_summary(const Summary& s) {
  std::ostringstream out;
  out << count(s.participants, "participant") << ", " << count(s.trials, "trial");
  if (s.excluded > 0) out << " (" << count(s.excluded, "excluded trial") << " left out)";
  out << "\n";
  char line[160];
  std::snprintf(line, sizeof line, "  %-5s %-12s %6s %10s %8s   %s\n", "task", "rendering", "trials", "time mean", "sd",
                "accuracy (mean)");
  out << line;
  for (const SummaryCell& c : s.cells) {
    std::snprintf(line, sizeof line, "  %-5s %-12s %6d %9.1fs %7.1fs   %s %.3f\n", c.task.c_str(), c.rendering.c_str(),
                  c.trials, c.time_mean, c.time_sd, c.measure.empty() ? "-" : c.measure.c_str(), c.measure_mean);
    out << line;
  }
  return out.str();
}

}  // namespace dtlab::sim
