// What the report analyses, derived from the recorded protocol (never from
// hard-coded study facts): factors and their roles, the primary factor (the
// rendering factor when there is one), tasks with their types and the factors
// that vary inside each task, questionnaire items, display labels, the
// published results the protocol declares to compare with ([reference_results]:
// shown beside ours, and the only way another study is ever named), and who
// the participants are (simulated or not).
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
  bool reference = false;        // the protocol declares published results ([reference_results]) to compare with
  bool article_names = false;    // ... and has the reference study's design: its level names (Standard, DynTrans)

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

  // --- published results ([reference_results]); all empty or null when the protocol declares none
  // The published row of `measure` ("time", "accuracy", an item id) and scope, or nullptr.
  const protocol::ReferenceResult* published(const std::string& measure, const std::string& scope) const;
  // Headings of the published columns: a level label per primary level, then "F(df1,df2)" if with_f, then "p".
  std::vector<std::string> published_header(bool with_f = true) const;
  // The published cells of a row, in published_header's order; "—" where nothing is published.
  std::vector<std::string> published_cells(const std::string& measure, const std::string& scope, int decimals,
                                           bool with_f = true) const;
  // The column group's heading: "article (Table III, VII.1)" (label and the locations of `measure`'s rows).
  std::string published_group(const std::string& measure) const { return published_group(std::vector{measure}); }
  std::string published_group(const std::vector<std::string>& measures) const;
  // The note under a table with published columns: who printed them, with how many participants.
  std::string published_note(const std::string& measure) const { return published_note(std::vector{measure}); }
  std::string published_note(const std::vector<std::string>& measures) const;
  // One cell: "0.94 (0.25)" for a whole-study value, "off 1.52 (0.59), on 3.09 (0.38)" per level,
  // then "; p < .01" when a p is printed; "" when nothing is published.
  std::string published_summary(const std::string& measure, const std::string& scope, int decimals) const;
  // "; cf. <source>" for figure captions, "" without published results.
  std::string published_cf() const;
};

Design make_design(const protocol::Protocol& p);

// Display names of task types: "count targets", "identify letter", ...
std::string task_type_label(protocol::TaskType t);

// The participants the database marks as simulated: demographics with
// "simulated" = true/1/yes, or a "source"/"provenance"/"kind"/"agent" field
// mentioning "sim". Returns ids in enrollment order.
std::vector<std::string> simulated_participants(const StudyData& d);

}  // namespace dtlab::report::detail
