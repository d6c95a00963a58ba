// What the report analyses, derived from the recorded protocol (never from
// hard-coded study facts): factors and their roles, the primary factor (the
// rendering factor when there is one), tasks with their types and the factors
// that vary inside each task, questionnaire items, display labels, whether
// the design is the reference study's (then the article's values are shown
// beside ours), and who the participants are (simulated or not).
// Pure functions of StudyData; no I/O.
#pragma once
#include <string>
#include <vector>

#include "analysis/report/detail/study_data.h"
#include "study/protocol/protocol.h"

namespace dtlab::report::detail {

struct TaskInfo {
  std::string id;
  protocol::TaskType type = protocol::TaskType::count_targets;
  std::string scenario;          // scenario table name
  int trials = 0;                // recorded trials per condition
  std::vector<int> factors;      // factors whose level varies between this task's conditions (protocol order)
};

struct Design {
  const protocol::Protocol* protocol = nullptr;
  std::vector<int> all_factors;  // 0 .. factors-1
  int primary = 0;               // the rendering-role factor, else the first factor
  int scenario_factor = -1;      // the scenario-role factor, or -1
  std::vector<TaskInfo> tasks;   // protocol order (scenarios in file order, their tasks in file order)
  bool reference = false;        // the reference study's design (STUDY.md): article values are shown

  const protocol::Factor& factor(int f) const { return protocol->factors[static_cast<size_t>(f)]; }
  // "off (standard)" for a rendering level, "Standard (off)" in the reference design, else the level name.
  std::string level_label(int f, int level) const;
  const TaskInfo* task(const std::string& id) const;
  // The scenario a trial ran in (its scenario-factor level, or the protocol's only scenario).
  std::string scenario_of(const TrialRow& t) const;
  // Number of tasks of a scenario.
  int tasks_in(const std::string& scenario) const;
  // "T1 (count targets)".
  std::string task_label(const TaskInfo& t) const;
  // "Tasks: T1 count targets (abstract), T2 ...": the note under tables that name tasks by id.
  std::string tasks_note() const;
};

Design make_design(const protocol::Protocol& p);

// Display names of task types: "count targets", "identify letter", ...
std::string task_type_label(protocol::TaskType t);

// The participants the database marks as simulated: demographics with
// "simulated" = true/1/yes, or a "source"/"provenance"/"kind"/"agent" field
// mentioning "sim". Returns ids in enrollment order.
std::vector<std::string> simulated_participants(const StudyData& d);

}  // namespace dtlab::report::detail
