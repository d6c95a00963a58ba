// plan_power: read one design revision, run the report's completion-time and
// accuracy sections (their tests are what is planned), plan (planning.h).
#include "analysis/report/planning.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "analysis/report/detail/design.h"
#include "analysis/report/detail/planning.h"
#include "analysis/report/detail/sections.h"
#include "analysis/report/detail/study_data.h"
#include "study/protocol/protocol.h"

namespace dtlab::report {

Result<PowerPlan> plan_power(store::StudyReader& reader, const PlanningOptions& options) {
  using namespace detail;
  if (options.sizes.empty()) return Error{"", 0, 0, "participants", "expected at least one number of participants"};
  for (int n : options.sizes)
    if (n < 2 || n > 100000)
      return Error{"", 0, 0, "participants", "expected numbers of participants from 2 to 100000, got " + std::to_string(n)};
  if (!(options.alpha > 0 && options.alpha < 1))
    return Error{"", 0, 0, "alpha", "expected a significance level between 0 and 1 (exclusive)"};
  auto designs = design_revisions(reader);
  if (!designs) return designs.error();
  if (options.revision == "all")
    return Error{reader.path(), 0, 0, "revision", "power is planned for one design revision: latest or N"};
  auto chosen = chosen_revisions(options.revision, static_cast<int>(designs->size()), reader.path());
  if (!chosen) return chosen.error();
  auto data = read_study(reader, chosen->front(), options.with_excluded);
  if (!data) return data.error();

  const Design design = make_design(data->protocol);
  ReportOptions ro;
  ro.with_excluded = options.with_excluded;
  ro.seed = options.seed;
  Context ctx(*data, design, ro);
  collect_subjects(ctx);
  if (ctx.analysed_trials == 0)
    return Error{data->path, 0, 0, "trial_table",
                 "no recorded trial to analyse in design revision " + std::to_string(data->design_revision) +
                     "; run sessions first"};
  section_time(ctx);
  section_errors(ctx);

  PowerPlan plan;
  plan.database = data->path;
  plan.design_revision = data->design_revision;
  plan.participants = ctx.subjects.size();
  plan.order_rows = std::max<long long>(1, protocol::declared_order_rows(data->protocol));
  plan.order_scheme = std::string(protocol::to_string(data->protocol.order.scheme));
  plan.options = options;
  plan.options.progress = nullptr;
  plan.effects = plan_effects(ctx, options, plan.not_planned);
  return plan;
}

nlohmann::json to_json(const PowerPlan& plan) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : plan.effects) effects.push_back(detail::to_json(e));
  return {{"database", plan.database},
          {"design_revision", plan.design_revision},
          {"participants", plan.participants},
          {"order_rows", plan.order_rows},
          {"order_scheme", plan.order_scheme},
          {"sizes", plan.options.sizes},
          {"replications", plan.options.replications},
          {"alpha", plan.options.alpha},
          {"seed", plan.options.seed},
          {"effects", effects},
          {"not_planned", plan.not_planned}};
}

}  // namespace dtlab::report
