// summarize (summary.h): one pass over the exported trial table.
#include "study/sim/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "analysis/stats/csv.h"
#include "study/common/text.h"
#include "study/store/export.h"

namespace dtlab::sim {

Result<Summary> summarize(const std::string& db_path, const std::string& rendering_factor) {
  std::ostringstream csv;
  auto exported = store::export_trials_csv(db_path, csv);
  if (!exported) return exported.error();
  auto table = stats::parse_csv(csv.str(), db_path + " (trial_table)");
  if (!table) return table.error();
  const stats::CsvTable& t = table.value();
  const int c_participant = t.column("participant"), c_task = t.column("task"), c_practice = t.column("practice"),
            c_time = t.column("completion_time_s"), c_rel = t.column("rel_error"), c_correct = t.column("correct"),
            c_distance = t.column("distance"), c_render = rendering_factor.empty() ? -1 : t.column(rendering_factor);
  for (int c : {c_participant, c_task, c_practice, c_time, c_rel, c_correct, c_distance})
    if (c < 0) return Error{db_path, 0, 0, "trial_table", "the export lacks a column the summary reads"};

  struct Acc {
    std::vector<double> times, measure;
    std::string name;
  };
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, Acc> acc;
  std::set<std::string> participants;
  Summary s;
  for (const auto& row : t.rows) {
    auto at = [&](int c) -> const std::string& { return row[static_cast<std::size_t>(c)]; };
    if (at(c_practice) == "1") continue;
    const std::pair<std::string, std::string> key{at(c_task), c_render >= 0 ? at(c_render) : std::string()};
    if (!acc.count(key)) order.push_back(key);
    Acc& a = acc[key];
    a.times.push_back(std::stod(at(c_time)));
    for (const auto& [c, name] : {std::pair{c_rel, "rel_error"}, {c_correct, "correct"}, {c_distance, "distance"}})
      if (at(c) != "NA") {
        a.measure.push_back(std::stod(at(c)));
        a.name = name;
      }
    participants.insert(at(c_participant));
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
  out << count(s.participants, "participant") << ", " << count(s.trials, "trial") << "\n";
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
