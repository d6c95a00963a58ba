// The report's mixed models as plain results; see mixed_models.h.
#include "analysis/report/detail/mixed_models.h"

#include <cmath>
#include <functional>

#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

using Field = std::function<std::optional<double>(const TrialRow&)>;

// What one model is fitted to.
struct ModelSpec {
  std::string section, scope, label, measure, column;
  std::vector<int> factors;  // design factors (fixed effects)
  bool task_factor = false;  // and the task as a factor (over all tasks)
  Field field;
  stats::Family family = stats::Family::gaussian;
  stats::Transform transform = stats::Transform::none;
  const TestReport* beside = nullptr;
};

constexpr double kAlpha = 0.05;

// The analysed trials of the spec's scope as LmmData (one row per trial; a trial without a value is missing).
stats::LmmData trial_data(const Context& ctx, const ModelSpec& spec) {
  const Design& d = ctx.design;
  stats::LongData data;
  data.source = "trials.csv";
  data.dv_name = spec.column;
  for (int f : spec.factors) data.within.push_back({d.factor(f).name, {}});
  if (spec.task_factor) data.within.push_back({"task", {}});
  std::vector<double> values;
  for (const auto& t : ctx.data.trials) {
    if (!ctx.analysed(t) || (!spec.task_factor && t.planned.task != spec.scope)) continue;
    const std::optional<double> v = spec.field(t);
    values.push_back(v ? *v : std::nan(""));
    data.subject.push_back(t.participant);
    for (size_t i = 0; i < spec.factors.size(); ++i)
      data.within[i].level.push_back(t.levels[static_cast<size_t>(spec.factors[i])]);
    if (spec.task_factor) data.within.back().level.push_back(t.planned.task);
  }
  data.dv = stats::Measurements::from_doubles(values);
  return {std::move(data), "participant", "", {}};
}

// Every effect both tests, by decision at alpha.
std::vector<ModelDecision> decisions(const stats::LmmFit& fit, const TestReport& r, const std::string& primary) {
  std::vector<ModelDecision> out;
  auto add = [&](const std::string& effect, double pa, double pm) {
    if (!std::isfinite(pa) || !std::isfinite(pm)) return;
    out.push_back({effect, pa, pm, (pa < kAlpha) != (pm < kAlpha)});
  };
  if (fit.family == stats::Family::binomial) {
    for (const auto& l : fit.lrt) {
      if (const stats::Effect* e = r.effect(l.term)) add(l.term, reported_p(*e), l.p);
      else if (l.term == primary && r.friedman) add(l.term, r.friedman->p, l.p);
    }
    return out;
  }
  for (const auto& a : fit.anova)
    if (const stats::Effect* e = r.effect(a.term)) add(a.term, reported_p(*e), a.p);
  return out;
}

MixedModelResult fit_one(const Context& ctx, const ModelSpec& spec) {
  MixedModelResult m;
  m.section = spec.section;
  m.scope = spec.scope;
  m.label = spec.label;
  m.measure = spec.measure;
  m.column = spec.column;
  m.subset = spec.task_factor ? "" : "task == \"" + spec.scope + "\"";
  m.beside = spec.beside;
  m.options.family = spec.family;
  m.options.transform = spec.transform;
  m.data = trial_data(ctx, spec);
  auto fit = stats::fit_lmm(m.data, m.options);
  if (!fit) {
    m.not_fitted = fit.error().message;
    return m;
  }
  m.fit = std::move(fit).value();
  m.trials = static_cast<long long>(m.fit->n);
  const std::string primary = ctx.design.factor(ctx.design.primary).name;
  if (std::find(m.fit->factor_names.begin(), m.fit->factor_names.end(), primary) != m.fit->factor_names.end())
    if (auto e = stats::marginal_means(*m.fit, {primary})) m.primary = *e;
  if (spec.beside) m.decisions = decisions(*m.fit, *spec.beside, primary);
  return m;
}

}  // namespace

std::vector<MixedModelResult> compute_mixed_models(const Context& ctx, const TimeResult& time,
                                                   const AccuracyResult& accuracy) {
  const Design& d = ctx.design;
  std::vector<ModelSpec> specs;
  const Field time_s = [](const TrialRow& t) { return std::optional<double>(t.completion_s); };
  for (const auto& task : d.tasks)
    specs.push_back({"time", task.id, task.id, "log completion time", "completion_time_s", task.factors, false, time_s,
                     stats::Family::gaussian, stats::Transform::log, time.of(task.id)});
  if (d.tasks.size() > 1) {
    std::vector<int> factors;  // the task stands for its scenario
    for (int f : d.all_factors)
      if (f != d.scenario_factor) factors.push_back(f);
    specs.push_back({"time", "overall", "All tasks", "log completion time", "completion_time_s", factors, true, time_s,
                     stats::Family::gaussian, stats::Transform::log, time.of("overall")});
  }
  for (const auto& task : d.tasks) {
    ModelSpec s{"accuracy", task.id, task.id, "", "", task.factors, false, {}, stats::Family::gaussian,
                stats::Transform::none, accuracy.of(task.id)};
    if (task.type == protocol::TaskType::count_targets || task.type == protocol::TaskType::count_kind) {
      s.measure = "relative error";
      s.column = "rel_error";
      s.field = [](const TrialRow& t) { return t.scores.rel_error; };
    } else if (task.type == protocol::TaskType::identify_letter) {
      s.measure = "correct (0/1)";
      s.column = "correct";
      s.family = stats::Family::binomial;
      s.field = [](const TrialRow& t) {
        return t.scores.correct ? std::optional<double>(*t.scores.correct ? 1.0 : 0.0) : std::nullopt;
      };
    } else if (task.type == protocol::TaskType::find_unique) {
      s.measure = "distance";
      s.column = "distance";
      s.field = [](const TrialRow& t) { return t.scores.distance; };
    } else {
      continue;
    }
    specs.push_back(std::move(s));
  }
  std::vector<MixedModelResult> out;
  for (const auto& s : specs) out.push_back(fit_one(ctx, s));
  return out;
}

std::string r_call(const MixedModelResult& m) {
  const std::string data = m.subset.empty() ? "d" : "subset(d, " + m.subset + ")";
  if (m.fit->family == stats::Family::binomial)
    return "glmer(" + m.fit->formula + ", data = " + data + ", family = binomial, control = ctl)";
  return "lmer(" + m.fit->formula + ", data = " + data + ")";
}

MixedResult section_mixed_models(Context& ctx, const TimeResult& time, const AccuracyResult& accuracy) {
  MixedResult r;
  r.models = compute_mixed_models(ctx, time, accuracy);
  for (const auto& m : r.models)
    if (m.fit)
      r.tally.tests += static_cast<int>(m.fit->family == stats::Family::binomial ? m.fit->lrt.size()
                                                                                 : m.fit->anova.size());
  return r;
}

}  // namespace dtlab::report::detail
