// Reading a `dtlab stats` table; see stats_input.h.
#include "app/stats_input.h"

#include <CLI/CLI.hpp>

#include <iostream>

#include "analysis/stats/csv.h"
#include "app/commands.h"

namespace dtlab::app {
namespace {

namespace st = dtlab::stats;

st::RowSelection parse_selection(const StatsInput& o) {
  st::RowSelection s;
  if (o.exclude_practice && o.include_practice)
    stats_fail(kExitUsage, "--exclude-practice and --include-practice exclude each other");
  s.practice = o.exclude_practice   ? st::Practice::exclude
               : o.include_practice ? st::Practice::include
                                    : st::Practice::automatic;
  s.with_excluded = o.with_excluded;
  for (const auto& w : o.where) {
    auto c = st::parse_row_condition(w);
    if (!c) stats_fail(kExitUsage, c.error().to_string());
    s.where.push_back(*c);
  }
  return s;
}

st::Aggregate parse_aggregate(const std::string& text) {
  if (text == "mean") return st::Aggregate::mean;
  if (text == "median") return st::Aggregate::median;
  if (text != "none") stats_fail(kExitUsage, "--aggregate must be none, mean or median, got " + st::quote_text(text));
  return st::Aggregate::none;
}

}  // namespace

void stats_fail(int code, const std::string& message) {
  std::cerr << "dtlab stats: " << message << "\n";
  throw CLI::RuntimeError(code);
}

SelectedTable load_selected_table(const StatsInput& o) {
  const st::RowSelection selection = parse_selection(o);
  auto table = st::read_csv_file(o.data);
  if (!table)
    stats_fail(table.error().line == 0 && table.error().message.rfind("cannot open", 0) == 0 ? kExitFailure
                                                                                          : kExitInvalid,
               table.error().to_string());
  auto report = st::select_rows(*table, selection);
  if (!report) stats_fail(kExitInvalid, report.error().to_string());
  return {std::move(table).value(), *report};
}

Loaded load_stats_input(const StatsInput& o, bool groups_design) {
  const st::Aggregate aggregate = parse_aggregate(o.aggregate);
  const SelectedTable selected = load_selected_table(o);
  const st::CsvTable& table = selected.table;
  Result<st::LongData> data = Error{};
  if (o.wide) {
    st::WideRoles w;
    w.subject = o.subject;
    w.dv = o.dv.empty() ? "value" : o.dv;
    if (groups_design) {
      w.conditions_are_groups = true;
      w.factor = o.between.empty() ? "group" : o.between.front();
    } else {
      w.between = o.between;
      if (o.within.size() > 1) stats_fail(kExitUsage, "--wide takes one within factor name (its columns are the conditions)");
      w.factor = o.within.empty() ? "condition" : o.within.front();
    }
    data = st::long_data_from_wide_csv(table, w);
  } else {
    if (o.dv.empty()) stats_fail(kExitUsage, "--dv COL is required (or --wide)");
    st::ColumnRoles roles{o.dv, groups_design ? std::string() : o.subject,
                          groups_design ? std::vector<std::string>{} : o.within, o.between};
    data = st::long_data_from_csv(table, roles);
  }
  if (!data) stats_fail(kExitInvalid, data.error().to_string());
  data->aggregate = aggregate;
  return {std::move(data).value(), selected.selection};
}

}  // namespace dtlab::app
