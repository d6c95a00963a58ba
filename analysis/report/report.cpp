// write_report: read, analyse, draw, write (report.h). The database is read
// through one StudyReader snapshot: the tidy table (byte for byte what
// `dtlab export` writes) and each design revision's data come from it.
// Output files are written whole or not at all (write_file_atomically).
#include "analysis/report/report.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/report/detail/report_design.h"
#include "analysis/report/detail/document.h"
#include "analysis/report/detail/plots.h"
#include "analysis/report/detail/sections.h"
#include "analysis/report/detail/study_data.h"
#include "study/common/file.h"
#include "study/common/version.h"
#include "study/store/export.h"

namespace dtlab::report {
namespace {

namespace fs = std::filesystem;
using namespace detail;

Error output_error(const fs::path& p, const std::string& what) {
  return Error{p.string(), 0, 0, "output", what, ErrorKind::environment};
}

Status write_whole(const fs::path& p, const std::string& text) {
  return write_file_atomically(p.string(), [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json design_json(const Design& d) {
  nlohmann::json f = nlohmann::json::array();
  for (int i : d.all_factors)
    f.push_back({{"name", d.factor(i).name}, {"role", std::string(protocol::to_string(d.factor(i).role))},
                 {"levels", d.factor(i).levels}});
  nlohmann::json t = nlohmann::json::array();
  for (const auto& task : d.tasks) {
    nlohmann::json varying = nlohmann::json::array();
    for (int i : task.factors) varying.push_back(d.factor(i).name);
    t.push_back({{"id", task.id}, {"type", std::string(protocol::to_string(task.type))}, {"scenario", task.scenario},
                 {"trials", task.trials}, {"factors", varying}});
  }
  return {{"factors", f}, {"primary", d.factor(d.primary).name}, {"tasks", t}, {"reference_design", d.article_names},
          {"published_results", d.reference ? nlohmann::json(d.protocol->reference_results->source)
                                            : nlohmann::json(nullptr)}};
}

// A participant ID or task ID as part of a file name: letters, digits, '-' and '_' kept, the rest '_'.
std::string file_safe(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out.empty() ? "_" : out;
}

// The walked-path figures of every analysed participant and WALKTHROUGH task whose trials have
// recorded poses, drawn by options.path_figure; none without that function.
struct DrawnPaths {
  std::vector<std::pair<PathFigure, std::string>> figures;  // with the SVG text
  std::vector<std::string> left_out;                        // "participant trial N: why"
};
Result<DrawnPaths> draw_paths(store::StudyReader& reader, const Context& ctx) {
  DrawnPaths out;
  if (!ctx.options.path_figure) return out;
  std::vector<std::pair<std::string, bool>> walk_tasks;  // task id, whether answers mark a position
  for (const auto& scenario : ctx.data.protocol.scenarios)
    for (const auto& task : scenario.tasks)
      if (task.scene.kind == protocol::ScenarioKind::walkthrough)
        walk_tasks.emplace_back(task.id, task.type == protocol::TaskType::find_unique);
  for (const auto& p : ctx.data.participants) {
    if (std::find(ctx.subjects.begin(), ctx.subjects.end(), p.id) == ctx.subjects.end()) continue;
    for (const auto& [task, marks] : walk_tasks) {
      std::vector<int> positions;
      for (const auto& t : ctx.data.trials)
        if (t.participant == p.id && t.planned.task == task && ctx.analysed(t)) positions.push_back(t.planned.position);
      if (positions.empty()) continue;
      auto drawn = ctx.options.path_figure(reader, p.id, positions, p.id + ", task " + task + ": walked paths" +
                                                             (marks ? " (o target, x marked answer)" : ""));
      if (!drawn) return drawn.error();
      for (const auto& why : drawn->left_out) out.left_out.push_back(p.id + " " + why);
      if (drawn->svg.empty()) continue;
      char index[16];
      std::snprintf(index, sizeof index, "%02d", p.index + 1);  // enrollment order from 1
      PathFigure f{p.id, task, static_cast<int>(positions.size()),
                   "paths/" + std::string(index) + "-" + file_safe(p.id) + "-" + file_safe(task) + ".svg"};
      out.figures.emplace_back(std::move(f), std::move(drawn->svg));
    }
  }
  return out;
}

// Every section in a paper's order, each handed the declared results it builds on, then the walked paths.
Result<DrawnPaths> run_sections(store::StudyReader& reader, Context& ctx, const ProgressFn& say) {
  say("participants and design (" + std::to_string(ctx.subjects.size()) + " participants, " +
      std::to_string(ctx.analysed_trials) + " trials)");
  section_overview(ctx);
  section_participants(ctx);
  say("completion time");
  const TimeResult time = section_time(ctx);
  say("accuracy");
  const AccuracyResult accuracy = section_errors(ctx);
  say("mixed models");
  section_mixed_models(ctx, time, accuracy);
  say("speed and accuracy");
  section_speed_accuracy(ctx, time, accuracy);
  say("questionnaire");
  section_questionnaire(ctx);
  say("instruments and questions per condition");
  section_instruments(ctx);
  say("position effects");
  section_position(ctx, time);
  say("frame-time audit");
  const FramesResult frames = section_frames(ctx);
  warn_at_top(ctx.doc, frames);
  say("planning the next study");
  section_planning(ctx, time, accuracy);
  if (ctx.options.path_figure) say("walked paths");
  auto paths = draw_paths(reader, ctx);
  if (!paths) return paths.error();
  std::vector<PathFigure> path_figures;
  for (const auto& [f, svg] : paths->figures) path_figures.push_back(f);
  const bool with_paths = section_paths(ctx, path_figures, paths->left_out);
  section_notes(ctx, with_paths);
  return paths;
}

// report.json's list of every enrolled participant: analysed, simulated, excluded.
nlohmann::json participants_json(const StudyData& data, const Context& ctx) {
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& p : data.participants) {
    const bool analysed = std::find(ctx.subjects.begin(), ctx.subjects.end(), p.id) != ctx.subjects.end();
    const bool sim = std::find(ctx.simulated.begin(), ctx.simulated.end(), p.id) != ctx.simulated.end();
    const bool excluded = std::find(data.excluded_participants.begin(), data.excluded_participants.end(), p.id) !=
                          data.excluded_participants.end();
    parts.push_back({{"id", p.id}, {"index", p.index}, {"order_row", p.order_row},
                     {"session", p.session_status ? nlohmann::json(store::to_string(*p.session_status)) : nlohmann::json(nullptr)},
                     {"planned", p.planned}, {"recorded", p.recorded}, {"analysed", analysed}, {"simulated", sim},
                     {"excluded", excluded}});
  }
  return parts;
}

// report.json's entries about the study as a whole, beside the sections' own.
void study_json(nlohmann::json& j, const StudyData& data, const Design& design, const Context& ctx,
                const ReportSummary& sum) {
  j["report_format"] = 1;
  j["generated_by"] = std::string(dtlab::version_string());
  j["generated_at"] = utc_now();
  j["database"] = data.path;
  j["protocol"] = {{"id", data.protocol.id}, {"title", data.protocol.title}, {"sha256", data.protocol.sha256},
                   {"design_sha256", protocol::design_sha256(data.protocol)},
                   {"design_revision", data.design_revision}, {"design_revisions", data.design_revisions},
                   {"protocol_texts", data.protocol_texts}, {"software_version", data.software_version}};
  j["design"] = design_json(design);
  j["participants"] = participants_json(data, ctx);
  nlohmann::json excl = nlohmann::json::array();
  for (const auto& x : data.exclusions)
    excl.push_back({{"participant", x.participant},
                    {"trial", x.position ? nlohmann::json(*x.position) : nlohmann::json(nullptr)},
                    {"decision", x.exclude ? "exclude" : "include"}, {"reason", x.reason}, {"by", x.by}, {"at", x.at}});
  j["exclusions"] = excl;
  j["summary"] = {{"participants", sum.participants}, {"trials", sum.trials}, {"tests", sum.tests},
                  {"excluded_trials", data.excluded_trials}, {"with_excluded", data.with_excluded},
                  {"simulated", sum.simulated}, {"simulated_participants", ctx.simulated}};
  j["warnings"] = ctx.warnings;
  std::vector<std::string> figure_files;
  for (const auto& p : ctx.plots) figure_files.push_back("figures/" + p.id + ".svg");
  j["figures"] = figure_files;
  j["figure_formats"] = {"svg", "png", "pdf"};  // figures/<id>.<format>, drawn by one gnuplot run
}

// The report of one design revision into `out`.
Result<ReportSummary> write_one(store::StudyReader& reader, const StudyData& data, const fs::path& out,
                                const std::string& tidy, const std::string& gnuplot, const ProgressFn& say,
                                const ReportOptions& options) {
  const Design design = make_design(data.protocol);
  Context ctx(data, design, options);
  collect_subjects(ctx);
  if (ctx.analysed_trials == 0)
    return Error{data.path, 0, 0, "trial_table",
                 "no recorded trial to analyse in design revision " + std::to_string(data.design_revision) + " (" +
                     std::to_string(data.participants.size()) + " participant" +
                     (data.participants.size() == 1 ? "" : "s") + " enrolled, " + std::to_string(data.trials.size()) +
                     " trial" + (data.trials.size() == 1 ? "" : "s") + ", practice trials" +
                     (data.with_excluded ? "" : " and excluded data") + " left out); run sessions first"};
  for (const auto& id : simulated_participants(data))
    if (std::find(ctx.subjects.begin(), ctx.subjects.end(), id) != ctx.subjects.end()) ctx.simulated.push_back(id);

  const fs::path figures = out / "figures";
  std::error_code ec;
  fs::create_directories(figures, ec);
  if (ec || !fs::is_directory(figures))
    return output_error(out, "cannot create the output directory: " + (ec ? ec.message() : "not a directory"));

  auto paths = run_sections(reader, ctx, say);
  if (!paths) return paths.error();
  say("drawing " + std::to_string(ctx.plots.size()) + " figures with " + gnuplot);
  auto svg = render_plots(ctx.plots, figures.string(), gnuplot);
  if (!svg) return svg.error();

  ReportSummary sum;
  sum.out_dir = out.string();
  sum.participants = static_cast<int>(ctx.subjects.size());
  sum.trials = ctx.analysed_trials;
  sum.excluded_trials = data.excluded_trials;
  sum.tests = ctx.tests;
  sum.simulated = !ctx.simulated.empty() && ctx.simulated.size() == ctx.subjects.size();
  sum.revisions = {data.design_revision};
  sum.warnings = ctx.warnings;
  study_json(ctx.json, data, design, ctx, sum);

  say("writing " + out.string());
  std::vector<std::pair<std::string, std::string>> files = {
      {"trials.csv", tidy},
      {"tests.csv", tests_csv(ctx)},
      {"report.json", ctx.json.dump(2) + "\n"},
      {"report.md", render_markdown(ctx.doc)},
      {"index.html", render_html(ctx.doc, *svg)},
      {"report.tex", render_latex(ctx.doc)},
  };
  for (const auto& [name, content] : ctx.csv) files.push_back({name, content});
  if (!paths->figures.empty()) {
    fs::create_directories(out / "paths", ec);
    if (ec) return output_error(out / "paths", "cannot create the directory: " + ec.message());
  }
  for (const auto& [f, svg] : paths->figures) files.push_back({f.file, svg});
  for (const auto& [name, content] : files) {
    if (auto s = write_whole(out / name, content); !s) return s.error();
    sum.files.push_back(name);
  }
  for (const auto& p : ctx.plots)
    for (const char* ext : {".svg", ".png", ".pdf"}) sum.files.push_back("figures/" + p.id + ext);
  return sum;
}

// out/index.html and out/report.md when several design revisions got a report each.
Status write_revision_index(const fs::path& out, const std::vector<store::Revision>& designs,
                            const std::vector<ReportSummary>& reports, const std::string& path) {
  Document doc;
  doc.title = "Results: " + designs.back().protocol_id + " (" + std::to_string(designs.size()) + " design revisions)";
  doc.subtitle = "Database `" + path + "`.";
  Section s{"revisions", "Design revisions, analysed separately", 2, {}};
  s.add(Callout{"warning", "This database holds " + std::to_string(designs.size()) + " design revisions",
                {"The protocol was changed in a way that changes what runs (its design hash differs), with "
                 "--allow-protocol-change. Participants of different designs are not pooled: each revision has its "
                 "own report below. Rewordings that keep the design (comments, titles, prompts) are pooled within a "
                 "revision."}});
  Table t;
  t.id = "table-revisions";
  t.caption = "Design revisions: the latest protocol text of each, and its report.";
  t.header = {"Revision", "Protocol SHA-256", "Recorded", "Participants", "Trials", "Report"};
  t.text_columns = 3;
  t.last_is_text = true;
  for (const ReportSummary& r : reports) {
    const store::Revision& d = designs[static_cast<std::size_t>(r.revisions.front() - 1)];
    const std::string dir = "revision-" + std::to_string(r.revisions.front());
    t.rows.push_back({std::to_string(r.revisions.front()), d.protocol_sha256.substr(0, 12) + "…", d.created_at,
                      std::to_string(r.participants), std::to_string(r.trials), "`" + dir + "/index.html`"});
  }
  s.add(t);
  doc.sections.push_back(std::move(s));
  if (auto st = write_whole(out / "report.md", render_markdown(doc)); !st) return st;
  return write_whole(out / "index.html", render_html(doc, {}));
}

}  // namespace

Result<ReportSummary> write_report(store::StudyReader& reader, const std::string& out_dir, const ProgressFn& progress,
                                   const ReportOptions& options) {
  auto say = [&](const std::string& step) {
    if (progress) progress(step);
  };
  const std::string gnuplot = gnuplot_executable(options.gnuplot);
  if (auto s = check_gnuplot(gnuplot); !s) return s.error();

  say("reading " + reader.path());
  auto designs = design_revisions(reader);
  if (!designs) return designs.error();
  auto chosen = chosen_revisions(options.revision, static_cast<int>(designs->size()), reader.path());
  if (!chosen) return chosen.error();
  auto trials = reader.trials();  // read once: for trials.csv and every revision's analysis
  if (!trials) return trials.error();
  std::ostringstream tidy;
  if (auto exported = store::export_trials_csv(reader, *trials, tidy); !exported) return exported.error();

  const fs::path out(out_dir);
  std::vector<ReportSummary> reports;
  for (int k : *chosen) {
    auto data = read_study(reader, *trials, k, options.with_excluded);
    if (!data) return data.error();
    const bool separate = chosen->size() > 1;
    auto one = write_one(reader, *data, separate ? out / ("revision-" + std::to_string(k)) : out, tidy.str(), gnuplot,
                         separate ? ProgressFn([&](const std::string& step) {
                           say("revision " + std::to_string(k) + ": " + step);
                         })
                                  : ProgressFn(say),
                         options);
    if (!one) return one.error();
    reports.push_back(std::move(*one));
  }
  if (reports.size() == 1) {
    reports.front().out_dir = out_dir;
    return reports.front();
  }
  ReportSummary sum;
  sum.out_dir = out_dir;
  sum.simulated = true;
  for (const ReportSummary& r : reports) {
    const std::string dir = "revision-" + std::to_string(r.revisions.front()) + "/";
    for (const auto& f : r.files) sum.files.push_back(dir + f);
    sum.participants += r.participants;
    sum.trials += r.trials;
    sum.excluded_trials += r.excluded_trials;
    sum.tests += r.tests;
    sum.simulated = sum.simulated && r.simulated;
    sum.revisions.push_back(r.revisions.front());
    for (const auto& w : r.warnings) sum.warnings.push_back("revision " + std::to_string(r.revisions.front()) + ": " + w);
  }
  sum.warnings.insert(sum.warnings.begin(), "the database holds " + std::to_string(designs->size()) +
                                                " design revisions; each is analysed separately (revision-N/)");
  if (auto s = write_revision_index(out, *designs, reports, reader.path()); !s) return s.error();
  sum.files.insert(sum.files.begin(), {"index.html", "report.md"});
  return sum;
}

Result<ReportSummary> write_report(const std::string& db_path, const std::string& out_dir, const ProgressFn& progress,
                                   const ReportOptions& options) {
  store::ReadOptions ro;
  ro.design_hash_of = &protocol::design_sha256_of_text;
  auto reader = store::StudyReader::open(db_path, ro);
  if (!reader) return reader.error();
  return write_report(*reader, out_dir, progress, options);
}

}  // namespace dtlab::report
