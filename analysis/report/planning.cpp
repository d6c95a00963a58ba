// plan_power: read one design revision, run the report's completion-time and
// accuracy tests (what is planned; without the sections' layout), plan (planning.h).
#include "analysis/report/planning.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "analysis/report/detail/report_design.h"
#include "analysis/report/detail/format.h"
#include "analysis/report/detail/mixed_models.h"
#include "analysis/report/detail/planning.h"
#include "analysis/report/detail/sections.h"
#include "analysis/report/detail/study_data.h"
#include "study/protocol/protocol.h"

namespace dtlab::report {

namespace {

// The primary factor of each of the report's mixed models, planned by simulation.
std::vector<PlannedMixedModel> plan_mixed_models(const detail::Context& ctx, const detail::TimeResult& time,
                                                 const detail::AccuracyResult& accuracy,
                                                 const PlanningOptions& options) {
  const std::string primary = ctx.design.factor(ctx.design.primary).name;
  std::vector<std::size_t> sizes;
  for (int n : options.sizes) sizes.push_back(static_cast<std::size_t>(n));
  std::vector<PlannedMixedModel> out;
  const auto models = detail::compute_mixed_models(ctx, time, accuracy);
  for (const auto& m : models) {
    PlannedMixedModel p{m.section, m.measure, m.scope, m.fit ? m.fit->formula : "", primary, NAN, {}, m.not_fitted};
    if (m.fit) {
      for (const auto& a : m.fit->anova)
        if (a.term == primary) p.pilot_p = a.p;
      for (const auto& l : m.fit->lrt)
        if (l.term == primary) p.pilot_p = l.p;
      stats::LmmOptions o = m.options;
      o.lrt = m.fit->family == stats::Family::binomial;
      auto rows = stats::lmm_power(m.data, o, *m.fit, {sizes, options.mixed_replications, options.alpha, options.seed, primary});
      if (rows) p.at = *rows;
      else p.not_planned = rows.error().message;
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace

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
  const TimeResult time = time_tests(ctx);
  const AccuracyResult accuracy = accuracy_tests(ctx);

  PowerPlan plan;
  plan.database = data->path;
  plan.design_revision = data->design_revision;
  plan.participants = ctx.subjects.size();
  plan.order_rows = std::max<long long>(1, protocol::declared_order_rows(data->protocol));
  plan.order_scheme = std::string(protocol::to_string(data->protocol.order.scheme));
  plan.options = options;
  plan.options.progress = nullptr;
  plan.effects = plan_effects(planning_input(design, data->protocol, time, accuracy), options, plan.not_planned);
  if (options.mixed) plan.mixed = plan_mixed_models(ctx, time, accuracy, options);
  return plan;
}

nlohmann::json to_json(const PowerPlan& plan) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : plan.effects) effects.push_back(detail::to_json(e));
  nlohmann::json mixed = nlohmann::json::array();
  for (const auto& m : plan.mixed) {
    nlohmann::json at = nlohmann::json::array();
    for (const auto& r : m.at)
      at.push_back({{"n", r.n}, {"power", detail::num(r.power.power)}, {"ci_low", detail::num(r.power.ci_low)},
                    {"ci_high", detail::num(r.power.ci_high)}, {"replications", r.power.replications},
                    {"failed", r.power.undefined}});
    mixed.push_back({{"section", m.section}, {"measure", m.measure}, {"scope", m.scope}, {"formula", m.formula},
                     {"term", m.term}, {"pilot_p", detail::num(m.pilot_p)}, {"power", at},
                     {"not_planned", m.not_planned}, {"replications", plan.options.mixed_replications}});
  }
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
          {"mixed", mixed},
          {"not_planned", plan.not_planned}};
}

}  // namespace dtlab::report
