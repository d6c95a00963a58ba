// questionnaire_results (questionnaire_results.h): the answers through
// questionnaire::answer_table (the instruments' scores included), then one
// participant x condition matrix per measure and its test.
#include "analysis/report/detail/questionnaire_results.h"

#include <algorithm>
#include <cmath>

#include "analysis/report/detail/format.h"
#include "study/questionnaire/table.h"

namespace dtlab::report::detail {

namespace {

namespace q = dtlab::questionnaire;

// The analysed participants' answers as a tidy table.
q::Table table_of(const Context& ctx) {
  const Design& d = ctx.design;
  std::vector<q::ParticipantPlan> plans;
  for (const std::string& id : ctx.subjects) {
    q::ParticipantPlan pp{id, {}};
    for (const TrialRow& t : ctx.data.trials) {
      if (t.participant != id) continue;
      q::PlanPoint p{t.planned.position, t.planned.block, t.planned.task, {}};
      for (int f : d.all_factors) p.levels.emplace_back(d.factor(f).name, t.levels[static_cast<size_t>(f)]);
      pp.plan.push_back(std::move(p));
    }
    plans.push_back(std::move(pp));
  }
  std::vector<q::StoredAnswer> answers;
  for (const AnswerRow& a : ctx.data.answers) {
    q::StoredValue v = a.number ? q::StoredValue{*a.number} : q::StoredValue{a.text.value_or("")};
    answers.push_back({a.participant, a.item, a.scope, std::move(v), ""});
  }
  std::vector<std::string> factors;
  for (int f : d.all_factors) factors.push_back(d.factor(f).name);
  return q::answer_table(d.protocol->questionnaire, d.protocol->instruments, factors, plans, answers);
}

// The design factors a `when` varies over: every factor after a block or task set (a block is one
// condition), the level's factor, none at the end.
std::vector<int> factors_of(const Design& d, const q::When& w) {
  if (w.kind == q::When::Kind::end) return {};
  if (w.kind == q::When::Kind::level) {
    for (int f : d.all_factors)
      if (d.factor(f).name == w.factor) return {f};
    return {};
  }
  return d.all_factors;
}

// "transparency: on, scenario: abstract" of a row's levels ("" at the end).
std::string condition_text(const Design& d, const q::TableRow& r) {
  std::string s;
  for (size_t f = 0; f < r.levels.size(); ++f)
    if (!r.levels[f].empty()) s += (s.empty() ? "" : ", ") + d.factor(static_cast<int>(f)).name + ": " + r.levels[f];
  return s;
}

// Per subject x cell of `factors`: the mean of the rows' numbers in the cell.
CellMatrix matrix_of(const Context& ctx, const std::vector<int>& factors, const std::vector<const q::TableRow*>& rows) {
  const Design& d = ctx.design;
  CellMatrix m;
  m.factors = factors;
  size_t cells = 1;
  for (int f : factors) cells *= d.factor(f).levels.size();
  for (size_t c = 0; c < cells; ++c) {
    std::vector<int> lv;
    std::string name;
    size_t rest = c, stride = cells;
    for (int f : factors) {
      stride /= d.factor(f).levels.size();
      lv.push_back(static_cast<int>(rest / stride));
      name += (name.empty() ? "" : "/") + d.factor(f).levels[rest / stride];
      rest %= stride;
    }
    m.cell_levels.push_back(lv);
    m.cell_names.push_back(name.empty() ? "all" : name);
  }
  m.subjects = ctx.subjects;
  m.value.assign(m.subjects.size(), std::vector<double>(cells, std::nan("")));
  m.trials.assign(m.subjects.size(), std::vector<int>(cells, 0));
  std::vector<std::vector<double>> sum(m.subjects.size(), std::vector<double>(cells, 0));
  for (const q::TableRow* r : rows) {
    if (!r->number) continue;
    const auto s = static_cast<size_t>(std::find(m.subjects.begin(), m.subjects.end(), r->participant) - m.subjects.begin());
    if (s >= m.subjects.size()) continue;
    size_t c = 0;
    bool known = true;
    for (int f : factors) {
      const auto& levels = d.factor(f).levels;
      const auto it = std::find(levels.begin(), levels.end(), r->levels[static_cast<size_t>(f)]);
      if (it == levels.end()) known = false;
      c = c * levels.size() + static_cast<size_t>(it - levels.begin());
    }
    if (!known) continue;
    sum[s][c] += *r->number;
    ++m.trials[s][c];
  }
  for (size_t s = 0; s < m.subjects.size(); ++s)
    for (size_t c = 0; c < cells; ++c)
      if (m.trials[s][c] > 0) m.value[s][c] = sum[s][c] / m.trials[s][c];
  return m;
}

// One measure: its matrix and test (none at the end: each participant's mean described instead).
ConditionMeasure measure_of(Context& ctx, Tally& tally, ConditionMeasure cm, const q::When& when, bool ordinal,
                            const std::vector<const q::TableRow*>& rows) {
  const Design& d = ctx.design;
  std::vector<int> factors = factors_of(d, when);
  const CellMatrix& all = ctx.keep(matrix_of(ctx, {}, rows));
  std::vector<double> means;
  for (size_t s = 0; s < all.subjects.size(); ++s)
    if (all.trials[s][0] > 0) means.push_back(all.value[s][0]);
  cm.overall = stats::describe(means);
  if (factors.empty()) return cm;
  const CellMatrix& m = ctx.keep(matrix_of(ctx, factors, rows));
  if (!ordinal) {
    cm.test = &ctx.add_test("instruments", run_rm_anova(m, d, cm.id, "", "per condition"), tally);
    return cm;
  }
  // Points on a scale: Friedman's test across the compared factor's levels (the primary factor
  // when the occasion varies it), each participant's mean over the other factors.
  size_t k = 0;
  for (size_t i = 0; i < factors.size(); ++i)
    if (factors[i] == d.primary) k = i;
  const CellMatrix& one = factors.size() == 1 ? m : ctx.keep(marginal_matrix(m, k));
  cm.test = &ctx.add_test("instruments", run_friedman(one, d, cm.id, "", "per condition", ctx.options.seed),
                          tally);
  return cm;
}

}  // namespace

QuestionnaireResults questionnaire_results(Context& ctx) {
  const Design& d = ctx.design;
  const protocol::Protocol& p = *d.protocol;
  QuestionnaireResults out;
  const q::Table table = table_of(ctx);
  const auto rows_of = [&](const std::string& item) {
    std::vector<const q::TableRow*> rows;
    for (const q::TableRow& r : table.rows)
      if (r.item == item) rows.push_back(&r);
    return rows;
  };

  for (const q::InstrumentUse& use : p.instruments) {
    for (const q::Scale& scale : use.instrument->scales(use.keys)) {
      const std::string id = use.id + ":" + scale.id;
      const auto rows = rows_of(id);
      for (const q::TableRow* r : rows)
        out.scores.push_back({r->participant, use.instrument->name, id, r->occasion, r->occasion_scope,
                              condition_text(d, *r), *r->number});
      ConditionMeasure cm{id, use.instrument->title + ": " + scale.label, use.instrument->name, q::to_string(use.when),
                          scale.min, scale.max, nullptr, {}};
      out.measures.push_back(measure_of(ctx, out.tally, std::move(cm), use.when, /*ordinal=*/false, rows));
    }
  }
  for (const protocol::QuestionnaireItem& item : p.questionnaire) {
    if (item.instrument || !item.type) continue;
    const q::Measure measure = item.type->measure;
    const auto rows = rows_of(item.id);
    if (measure == q::Measure::text) {
      for (const q::TableRow* r : rows)
        if (r->text && r->text->find_first_not_of(" \t\n") != std::string::npos)
          out.texts.push_back({r->participant, item.id, condition_text(d, *r), *r->text});
      continue;
    }
    if (item.when.kind == q::When::Kind::end) continue;  // section_questionnaire reports these
    if (measure == q::Measure::nominal || measure == q::Measure::multiple) {
      std::map<std::string, ConditionCounts> by_condition;
      for (const q::TableRow* r : rows) {
        if (!r->text) continue;
        ConditionCounts& c = by_condition[condition_text(d, *r)];
        c.item = item.id;
        c.prompt = item.prompt;
        c.condition = condition_text(d, *r);
        ++c.answers;
        for (const std::string& o : item.strings("options"))
          if (*r->text == o || ("\n" + *r->text + "\n").find("\n" + o + "\n") != std::string::npos) ++c.chosen[o];
      }
      for (auto& [condition, c] : by_condition) out.counts.push_back(std::move(c));
      continue;
    }
    const q::NumberPair b = item.type->bounds ? item.type->bounds(item) : q::NumberPair{};
    ConditionMeasure cm{item.id, item.prompt, "", q::to_string(item.when), b.min, b.max, nullptr, {}};
    out.measures.push_back(measure_of(ctx, out.tally, std::move(cm), item.when, measure == q::Measure::ordinal, rows));
  }
  return out;
}

std::optional<QuestionnaireResults> section_instruments(Context& ctx) {
  QuestionnaireResults res = questionnaire_results(ctx);
  if (res.measures.empty() && res.counts.empty() && res.texts.empty()) return std::nullopt;
  return res;
}

}  // namespace dtlab::report::detail
