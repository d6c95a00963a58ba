// report.json, laid out from the sections' results and the study (render_data.h):
// one function per entry, each a plain mapping of a result's fields to JSON
// (NaN as null through num()). Key order is nlohmann::json's (sorted), so
// the order the entries are added in never shows in the file.
#include <chrono>
#include <ctime>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/planning.h"
#include "analysis/report/detail/render_data.h"
#include "analysis/stats/json.h"
#include "analysis/stats/lmm_json.h"
#include "study/common/version.h"

namespace dtlab::report::detail {
namespace {

using nlohmann::json;

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

json to_json(const InteractionFollowUp& f);

// A test and its parts as report.json records them (NaN as null).
json to_json(const stats::Descriptives& d) { return stats::descriptives_json<json>(d); }

json to_json(const stats::Effect& e) {
  json j = stats::effect_json<json>(e);
  j["apa"] = effect_sentence(e);
  return j;
}

// Descriptives of every cell of the test, with the cell's name and levels.
json cells_json(const TestReport& r, const Design& d) {
  const CellMatrix& m = *r.m;
  json cells = json::array();
  for (size_t c = 0; c < m.cells(); ++c) {
    json levels = json::object();
    for (size_t k = 0; k < m.factors.size(); ++k)
      levels[d.factor(m.factors[k]).name] = d.factor(m.factors[k]).levels[static_cast<size_t>(m.level(c, k))];
    json cj = to_json(r.cells[c]);
    cj["cell"] = m.cell_names[c];
    cj["levels"] = levels;
    cells.push_back(cj);
  }
  return cells;
}

// Descriptives per level of each factor of the test.
json marginals_json(const TestReport& r, const Design& d) {
  const CellMatrix& m = *r.m;
  json marg = json::object();
  for (size_t k = 0; k < m.factors.size(); ++k) {
    json per = json::array();
    for (size_t l = 0; l < r.marginals[k].size(); ++l) {
      json lj = to_json(r.marginals[k][l]);
      lj["level"] = d.factor(m.factors[k]).levels[l];
      per.push_back(lj);
    }
    marg[d.factor(m.factors[k]).name] = per;
  }
  return marg;
}

json to_json(const TestReport& r, const Design& d) {
  const CellMatrix& m = *r.m;
  json j{{"measure", r.measure}, {"unit", r.unit}, {"scope", r.scope}, {"test", r.test}};
  json factors = json::array();
  for (int f : m.factors) factors.push_back(d.factor(f).name);
  j["factors"] = factors;
  j["n"] = r.kept.size();
  j["excluded"] = r.excluded;
  j["cells"] = cells_json(r, d);
  j["marginals"] = marginals_json(r, d);
  if (r.anova) {
    json eff = json::array();
    for (const auto& e : r.anova->effects) eff.push_back(to_json(e));
    j["effects"] = eff;
  }
  if (r.friedman) j["friedman"] = stats::friedman_json<json>(*r.friedman);  // the fields `dtlab stats friedman` prints
  if (r.wilcoxon) {
    j["wilcoxon"] = stats::wilcoxon_json<json>(*r.wilcoxon);
    j["wilcoxon"]["x"] = m.cell_names[0];
    j["wilcoxon"]["y"] = m.cell_names[1];
    j["wilcoxon"]["rank_biserial"] = num(rank_biserial(*r.wilcoxon));
  }
  if (!r.posthoc.empty()) {
    json ph = json::object();
    for (const auto& [factor, list] : r.posthoc) {
      ph[factor] = stats::comparisons_json<json>(list);
    }
    j["posthoc"] = ph;
  }
  if (r.paired) {
    const auto& p = *r.paired;
    const auto& lv = d.factor(p.factor).levels;
    j["paired"] = stats::paired_t_json<json>(p.t);  // as `dtlab stats wilcoxon --json` prints it, and:
    j["paired"]["factor"] = d.factor(p.factor).name;
    j["paired"]["difference"] = lv[static_cast<size_t>(p.b)] + " - " + lv[static_cast<size_t>(p.a)];
    j["paired"]["dz"] = num(p.dz);  // the report's d_z: null, not t, where the differences do not vary
  }
  if (!r.followups.empty()) {
    json fj = json::array();
    for (const auto& f : r.followups) fj.push_back(to_json(f));
    j["followups"] = fj;
  }
  if (r.normality)
    j["shapiro_wilk_residuals"] = {{"n", r.normality->n}, {"W", num(r.normality->W)}, {"p", num(r.normality->p)},
                                   {"warnings", r.normality->warnings}};
  j["not_tested"] = r.not_tested.empty() ? json(nullptr) : json(r.not_tested);
  j["warnings"] = r.warnings;
  return j;
}

json to_json(const InteractionFollowUp& f) {
  json simple = json::array();
  for (const auto& se : f.simple.rows) {
    json row{{"factor", se.factor}, {"at_factor", se.at_factor}, {"at_level", se.at_level},
             {"test", se.test},     {"n", se.n},                 {"p", num(se.p)},
             {"p_holm", num(se.p_holm)}};
    if (se.test == "paired t")
      row["contrast"] = stats::comparison_json<json>(se.contrast);
    else
      row["anova"] = to_json(se.anova);
    simple.push_back(row);
  }
  json cells = json::array();
  for (const auto& c : f.intervals) {
    json levels = json::object();
    for (const auto& [factor, level] : c.levels) levels[factor] = level;
    cells.push_back({{"levels", levels}, {"n", c.n}, {"mean", num(c.mean)}, {"se_within", num(c.se)},
                     {"ci95_low", num(c.ci_low)}, {"ci95_high", num(c.ci_high)}});
  }
  return {{"effect", f.effect},
          {"simple_effects", simple},
          {"cell_means_within_ci", cells},
          {"ci_method", "Cousineau (2005) with Morey's (2008) correction"}};
}


json published_json(const protocol::ReferenceResult& r, const Design& d) {
  const auto& rr = *d.protocol->reference_results;
  json j{{"source", rr.source}, {"label", rr.label}, {"location", r.location}, {"F", r.F}, {"p", r.p}};
  if (!r.per_level && !r.mean.empty()) {
    j["mean"] = r.mean[0];
    j["sd"] = r.sd[0];
  } else if (!r.mean.empty()) {
    for (size_t l = 0; l < r.mean.size(); ++l) {
      j["mean"][d.factor(d.primary).levels[l]] = r.mean[l];
      j["sd"][d.factor(d.primary).levels[l]] = r.sd[l];
    }
  }
  return j;
}

json design_json(const Design& d) {
  json f = json::array();
  for (int i : d.all_factors)
    f.push_back({{"name", d.factor(i).name}, {"role", std::string(protocol::to_string(d.factor(i).role))},
                 {"levels", d.factor(i).levels}});
  json t = json::array();
  for (const auto& task : d.tasks) {
    json varying = json::array();
    for (int i : task.factors) varying.push_back(d.factor(i).name);
    t.push_back({{"id", task.id}, {"type", std::string(protocol::to_string(task.type))}, {"scenario", task.scenario},
                 {"trials", task.trials}, {"factors", varying}});
  }
  return {{"factors", f}, {"primary", d.factor(d.primary).name}, {"tasks", t}, {"reference_design", d.article_names},
          {"published_results", d.reference ? json(d.protocol->reference_results->source) : json(nullptr)}};
}

// Every enrolled participant: analysed, simulated, excluded.
json participants_json(const Context& ctx) {
  const StudyData& data = ctx.data;
  json parts = json::array();
  for (const auto& p : data.participants) {
    const bool analysed = std::find(ctx.subjects.begin(), ctx.subjects.end(), p.id) != ctx.subjects.end();
    const bool sim = std::find(ctx.simulated.begin(), ctx.simulated.end(), p.id) != ctx.simulated.end();
    const bool excluded = std::find(data.excluded_participants.begin(), data.excluded_participants.end(), p.id) !=
                          data.excluded_participants.end();
    parts.push_back({{"id", p.id}, {"index", p.index}, {"order_row", p.order_row},
                     {"session", p.session_status ? json(store::to_string(*p.session_status)) : json(nullptr)},
                     {"planned", p.planned}, {"recorded", p.recorded}, {"analysed", analysed}, {"simulated", sim},
                     {"excluded", excluded}});
  }
  return parts;
}

// The entries about the study as a whole, beside the sections' own.
void study_json(json& j, const Context& ctx, const ReportSummary& sum, const std::vector<PlotSpec>& plots) {
  const StudyData& data = ctx.data;
  j["report_format"] = 1;
  j["generated_by"] = std::string(dtlab::version_string());
  j["generated_at"] = utc_now();
  j["database"] = data.path;
  j["protocol"] = {{"id", data.protocol.id}, {"title", data.protocol.title}, {"sha256", data.protocol.sha256},
                   {"design_sha256", protocol::design_sha256(data.protocol)},
                   {"design_revision", data.design_revision}, {"design_revisions", data.design_revisions},
                   {"protocol_texts", data.protocol_texts}, {"software_version", data.software_version}};
  j["design"] = design_json(ctx.design);
  j["participants"] = participants_json(ctx);
  json excl = json::array();
  for (const auto& x : data.exclusions)
    excl.push_back({{"participant", x.participant}, {"trial", x.position ? json(*x.position) : json(nullptr)},
                    {"decision", x.exclude ? "exclude" : "include"}, {"reason", x.reason}, {"by", x.by}, {"at", x.at}});
  j["exclusions"] = excl;
  j["summary"] = {{"participants", sum.participants}, {"trials", sum.trials}, {"tests", sum.tests},
                  {"excluded_trials", data.excluded_trials}, {"with_excluded", data.with_excluded},
                  {"simulated", sum.simulated}, {"simulated_participants", ctx.simulated}};
  j["warnings"] = sum.warnings;
  std::vector<std::string> figure_files;
  for (const auto& p : plots) figure_files.push_back("figures/" + p.id + ".svg");
  j["figures"] = figure_files;
  j["figure_formats"] = {"svg", "png", "pdf"};  // figures/<id>.<format>, drawn by one gnuplot run
}

json tests_json(const std::vector<const TestReport*>& tests, const Design& d) {
  json list = json::array();
  for (const TestReport* r : tests) list.push_back(to_json(*r, d));
  return list;
}

json tests_json(const TestRows& rows, const Design& d) {
  json list = json::array();
  for (const auto& [label, r] : rows) list.push_back(to_json(*r, d));
  return list;
}

// The completion-time table's rows (F of the primary factor, published values beside) and every test.
json time_json(const TimeResult& t, const Design& d) {
  const std::string& primary = d.factor(d.primary).name;
  json rows = json::array();
  for (const auto& [label, r] : t.rows) {
    const TaskInfo* task = d.task(r->scope);
    json row{{"scope", r->scope}, {"label", task ? task->id : label}, {"n", r->kept.size()}};
    if (const stats::Effect* e = r->effect(primary)) row["effect"] = to_json(*e);
    if (const auto* a = d.published("time", r->scope)) row["published"] = published_json(*a, d);
    rows.push_back(row);
  }
  return {{"table", rows}, {"tests", tests_json(t.rows, d)}, {"rank_tests", tests_json(t.rank_tests, d)}};
}

// The accuracy table's rows (published values where declared) and their tests.
json accuracy_json(const AccuracyResult& a, const Design& d) {
  json rows = json::array(), tests = json::array();
  for (const AccuracyRow& row : a.rows) {
    const TestReport& r = *row.r;
    json jr{{"scope", r.scope}, {"label", row.label}, {"measure", row.measure}, {"n", r.kept.size()}};
    if (const auto* p = row.published.empty() ? nullptr : d.published("accuracy", row.published))
      jr["published"] = published_json(*p, d);
    rows.push_back(jr);
    tests.push_back(to_json(r, d));
  }
  return {{"table", rows}, {"tests", tests}};
}

json speed_accuracy_json(const std::vector<SpeedAccuracyRow>& rows) {
  json list = json::array();
  for (const SpeedAccuracyRow& row : rows) {
    json jr{{"task", row.task}, {"error_measure", row.error_measure}, {"levels", json::array()},
            {"reading", row.reading}};
    for (const auto& l : row.levels)
      jr["levels"].push_back({{"level", l.level}, {"time_s", num(l.time_s)}, {"error", num(l.error)}});
    if (const auto& x = row.differences) {
      jr["time_difference_s"] = num(x->time_s);
      jr["time_difference_p"] = num(x->time_p);
      jr["error_difference"] = num(x->error);
      jr["error_difference_p"] = num(x->error_p);
    }
    const RmCorr& rc = row.rmcorr;
    jr["rmcorr"] = {{"n", rc.n}, {"groups", rc.groups}, {"r", num(rc.r)}, {"df", num(rc.df)}, {"p", num(rc.p)},
                    {"ci_low", num(rc.ci_low)}, {"ci_high", num(rc.ci_high)}, {"slope_per_s", num(rc.slope)}};
    list.push_back(jr);
  }
  return list;
}

json position_json(const PositionResult& p, const Design& d) {
  json j{{"balance", p.balance}, {"balanced", p.balanced}};
  for (const auto& split : p.splits) {
    json levels = json::array();
    for (const auto& l : split.levels) {
      json x = to_json(l.relative);
      x["position"] = l.position;
      x["time_s"] = to_json(l.time_s);
      levels.push_back(x);
    }
    j[split.key] = {{"levels", levels}, {"test", to_json(*split.test, split.design->design)}};
  }
  if (p.order_row) j["order_row"] = to_json(*p.order_row, d);
  return j;
}

// One questionnaire item: its tests (ratings), descriptives (numbers, depth tests) or choices.
json questionnaire_item_json(const QuestionnaireItemResult& item, const Design& d) {
  using Kind = QuestionnaireItemResult::Kind;
  json j{{"type", item.type}, {"prompt", item.prompt}, {"n", item.n}};
  if (item.kind == Kind::rating) j["tests"] = tests_json(item.tests, d);
  if (item.kind == Kind::numeric) {
    j["descriptives"] = to_json(item.descriptives);
    if (item.proportion_correct) j["proportion_correct"] = num(*item.proportion_correct);
  }
  if (item.kind == Kind::choice) {
    json choices = json::object();
    for (const auto& [option, c] : item.choices)
      choices[option] = {{"count", c.count}, {"proportion", num(c.proportion)}, {"sd", num(c.sd)}};
    j["choices"] = choices;
    if (const auto& st = item.sign_test)
      j["sign_test"] = {{"n", st->n}, {"for_" + item.second_option, st->positive},
                        {"for_" + item.first_option, st->negative}, {"p", num(st->p)}, {"log10_p", num(st->log10_p)}};
  }
  if (item.kind == Kind::numeric || item.kind == Kind::choice)
    if (const auto* a = d.published(item.id, "overall")) j["published"] = published_json(*a, d);
  return j;
}

json sample_json(const ParticipantsResult& r) {
  json j{{"described", r.described}, {"consent_asked", r.consent_asked}, {"consented", r.consented},
         {"declined", r.declined}, {"withdrawn", r.withdrawn}};
  for (const auto& f : r.numeric)
    j["demographics"][f.id] = {{"n", f.d.n}, {"mean", num(f.d.mean)}, {"sd", num(f.d.sd)}, {"min", num(f.d.min)},
                               {"max", num(f.d.max)}};
  for (const auto& c : r.choices) {
    json counts = json::object();
    for (const auto& [option, n] : c.counts) counts[option] = n;
    j["demographics"][c.id] = {{"n", c.answered}, {"counts", counts}};
  }
  for (const auto& f : r.texts) j["demographics"][f.id] = {{"n", f.answered}};
  for (const auto& a : r.around)
    j["around_sessions"].push_back({{"participant", a.id}, {"pauses", a.pauses}, {"paused_s", num(a.paused_s)},
                                    {"notes", a.notes}});
  j["study_notes"] = r.study_notes;
  return j;
}

json mixed_json(const MixedModelResult& m) {
  json j{{"section", m.section}, {"scope", m.scope}, {"label", m.label}, {"measure", m.measure},
         {"column", m.column}, {"subset", m.subset}, {"trials", m.trials}};
  if (!m.fit) {
    j["not_fitted"] = m.not_fitted;
    return j;
  }
  j["r_call"] = r_call(m);
  j["fit"] = stats::lmm_fit_json<json>(*m.fit);
  if (m.primary) j["primary"] = stats::emm_table_json<json>(*m.primary);
  json dec = json::array();
  for (const auto& x : m.decisions)
    dec.push_back({{"effect", x.effect}, {"p_anova", num(x.p_anova)}, {"p_model", num(x.p_model)},
                   {"disagree", x.disagree}});
  j["decisions"] = dec;
  return j;
}

json instruments_json(const QuestionnaireResults& res, const Design& d) {
  json measures = json::array();
  for (const ConditionMeasure& m : res.measures) {
    json j{{"id", m.id}, {"label", m.label}, {"instrument", m.instrument}, {"occasion", m.occasion},
           {"min", m.min}, {"max", m.max}, {"overall", to_json(m.overall)}};
    if (m.test) j["test"] = to_json(*m.test, d);
    measures.push_back(j);
  }
  json counts = json::array();
  for (const ConditionCounts& c : res.counts)
    counts.push_back({{"item", c.item}, {"condition", c.condition}, {"chosen", c.chosen}, {"answers", c.answers}});
  json texts = json::array();
  for (const FreeText& f : res.texts)
    texts.push_back({{"participant", f.participant}, {"item", f.item}, {"condition", f.condition}, {"text", f.text}});
  return {{"measures", measures}, {"choices", counts}, {"free_text", texts}};
}

json frames_json(const FramesResult& fr) {
  json conditions = json::array();
  for (const auto& c : fr.conditions)
    conditions.push_back({{"condition", c.condition}, {"method", c.method}, {"display", c.display},
                          {"trials", c.trials}, {"trials_with_frames", c.trials_with_frames}, {"frames", c.frames},
                          {"display_hz", num(c.display_hz)}, {"display_hz_known", c.display_hz_known},
                          {"median_fps", num(c.median_fps)}, {"median_steady_ms", num(c.median_steady_ms)},
                          {"below_display", c.below_display}, {"late_frames", c.late_frames},
                          {"late_share", num(c.late_share)}, {"median_first_ms", num(c.median_first_ms)},
                          {"median_p95_ms", num(c.median_p95_ms)}, {"slow_trials", c.slow_trials},
                          {"slow_share", num(c.slow_share)}});
  return {{"threshold_ms", fr.threshold_ms}, {"min_fps", fr.min_fps}, {"rate_spread", fr.rate_spread},
          {"trials_with_frames", fr.trials_with_frames}, {"warnings", fr.warnings},
          {"below_display", fr.below}, {"conditions", conditions}};
}

json planning_json(const PlanningResult& p) {
  json effects = json::array();
  for (const auto& e : p.effects) effects.push_back(detail::to_json(e));  // planning.h's, as `dtlab power`
  return {{"method", "analytic"}, {"sizes", p.sizes}, {"alpha", p.alpha}, {"effects", effects},
          {"not_planned", p.not_planned}};
}

json path_figures_json(const std::vector<PathFigure>& figures) {
  json list = json::array();
  for (const PathFigure& f : figures)
    list.push_back({{"participant", f.participant}, {"task", f.task}, {"trials", f.trials}, {"file", f.file}});
  return list;
}

}  // namespace

json render_json(const Context& ctx, const SectionResults& results, const ReportSummary& summary,
                 const std::vector<PlotSpec>& plots) {
  json j = json::object();
  j["sample"] = sample_json(results.sample);
  j["completion_time"] = time_json(results.time, ctx.design);
  if (!results.accuracy.rows.empty()) j["accuracy"] = accuracy_json(results.accuracy, ctx.design);
  if (!results.speed_accuracy.rows.empty()) j["speed_accuracy"] = speed_accuracy_json(results.speed_accuracy.rows);
  j["position"] = position_json(results.position, ctx.design);
  if (results.questionnaire.items) {
    json items = json::object();
    for (const auto& item : *results.questionnaire.items) items[item.id] = questionnaire_item_json(item, ctx.design);
    j["questionnaire"] = items;
  }
  if (results.time.log_rows) j["completion_time_log"] = {{"tests", tests_json(*results.time.log_rows, ctx.design)}};
  json mixed = json::array();
  for (const auto& m : results.mixed.models) mixed.push_back(mixed_json(m));
  j["mixed_models"] = mixed;
  if (results.instruments) j["instruments"] = instruments_json(*results.instruments, ctx.design);
  j["frames"] = frames_json(results.frames);
  j["planning"] = planning_json(results.planning);
  if (results.paths.shown) {
    j["path_figures"] = path_figures_json(results.paths.figures);
    j["path_figures_left_out"] = results.paths.left_out;
  }
  study_json(j, ctx, summary, plots);
  return j;
}

}  // namespace dtlab::report::detail
