// write_report: read, analyse, draw, write (report.h). The database is read
// through one StudyReader snapshot: the tidy table (byte for byte what
// `dtlab export` writes) and each design revision's data come from it. The
// sections compute first, all of them; then their layout functions build the
// Document, which three renderers print, and render_json and render_csv lay
// the results out; this file writes what they return.
// Output files are written whole or not at all (write_file_atomically).
#include "analysis/report/report.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/report/detail/report_design.h"
#include "analysis/report/detail/document.h"
#include "analysis/report/detail/layout.h"
#include "analysis/report/detail/plots.h"
#include "analysis/report/detail/render_data.h"
#include "analysis/report/detail/sections.h"
#include "analysis/report/detail/study_data.h"
#include "study/common/file.h"
#include "study/store/export.h"

namespace dtlab::report {

std::vector<const detail::Tally*> detail::SectionResults::tallies() const {
  std::vector<const Tally*> out = {&overview.tally, &sample.tally,          &time.tally,
                                   &accuracy.tally, &mixed.tally,           &speed_accuracy.tally,
                                   &questionnaire.tally};
  if (instruments) out.push_back(&instruments->tally);
  for (const Tally* t : {&position.tally, &frames.tally, &planning.tally, &paths.tally}) out.push_back(t);
  return out;
}

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

// Every section computed in a paper's order, each handed the declared results it builds on, then the walked
// paths (their SVG texts to `paths`). Nothing is laid out yet.
Result<SectionResults> run_sections(store::StudyReader& reader, Context& ctx, const ProgressFn& say,
                                    DrawnPaths& paths) {
  SectionResults r;
  say("participants and design (" + std::to_string(ctx.subjects.size()) + " participants, " +
      std::to_string(ctx.analysed_trials) + " trials)");
  r.overview = section_overview(ctx);
  r.sample = section_participants(ctx);
  say("completion time");
  r.time = section_time(ctx);
  say("accuracy");
  r.accuracy = section_errors(ctx);
  say("mixed models");
  r.mixed = section_mixed_models(ctx, r.time, r.accuracy);
  say("speed and accuracy");
  r.speed_accuracy = section_speed_accuracy(ctx, r.time, r.accuracy);
  say("questionnaire");
  r.questionnaire = section_questionnaire(ctx);
  say("instruments and questions per condition");
  r.instruments = section_instruments(ctx);
  say("position effects");
  r.position = section_position(ctx, r.time);
  say("frame-time audit");
  r.frames = section_frames(ctx);
  say("planning the next study");
  r.planning = section_planning(ctx, r.time, r.accuracy);
  if (ctx.options.path_figure) say("walked paths");
  auto drawn = draw_paths(reader, ctx);
  if (!drawn) return drawn.error();
  paths = std::move(*drawn);
  std::vector<PathFigure> figures;
  for (const auto& [f, svg] : paths.figures) figures.push_back(f);
  r.paths = section_paths(std::move(figures), paths.left_out);
  return r;
}

// Every section's result laid out in the same order: the Document and the plots its figures draw.
Layout lay_out(const Context& ctx, const SectionResults& r) {
  Layout out;
  lay_out_overview(out, ctx, r.overview, r.frames);
  lay_out_participants(out, r.sample);
  lay_out_time(out, ctx, r.time);
  lay_out_accuracy(out, ctx, r.accuracy);
  lay_out_mixed_models(out, ctx, r.mixed);
  lay_out_speed_accuracy(out, ctx, r.speed_accuracy, r.time, r.accuracy);
  lay_out_questionnaire(out, ctx, r.questionnaire);
  if (r.instruments) lay_out_instruments(out, ctx, *r.instruments);
  lay_out_position(out, ctx, r.position);
  lay_out_frames(out, r.frames);
  lay_out_planning(out, ctx, r.planning);
  lay_out_paths(out, r.paths);
  lay_out_notes(out, ctx, r.paths.shown);
  return out;
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

  DrawnPaths paths;
  auto results = run_sections(reader, ctx, say, paths);
  if (!results) return results.error();
  const Layout layout = lay_out(ctx, *results);
  say("drawing " + std::to_string(layout.plots.size()) + " figures with " + gnuplot);
  auto svg = render_plots(layout.plots, figures.string(), gnuplot);
  if (!svg) return svg.error();

  ReportSummary sum;
  sum.out_dir = out.string();
  sum.participants = static_cast<int>(ctx.subjects.size());
  sum.trials = ctx.analysed_trials;
  sum.excluded_trials = data.excluded_trials;
  sum.simulated = !ctx.simulated.empty() && ctx.simulated.size() == ctx.subjects.size();
  sum.revisions = {data.design_revision};
  for (const Tally* t : results->tallies()) {
    sum.tests += t->tests;
    sum.warnings.insert(sum.warnings.end(), t->warnings.begin(), t->warnings.end());
  }

  say("writing " + out.string());
  std::map<std::string, std::string> csv = render_csv(ctx, *results);
  std::vector<std::pair<std::string, std::string>> files = {
      {"trials.csv", tidy},
      {"tests.csv", csv.extract("tests.csv").mapped()},
      {"report.json", render_json(ctx, *results, sum, layout.plots).dump(2) + "\n"},
      {"report.md", render_markdown(layout.doc)},
      {"index.html", render_html(layout.doc, *svg)},
      {"report.tex", render_latex(layout.doc)},
  };
  for (auto& [name, content] : csv) files.push_back({name, std::move(content)});
  if (!paths.figures.empty()) {
    fs::create_directories(out / "paths", ec);
    if (ec) return output_error(out / "paths", "cannot create the directory: " + ec.message());
  }
  for (const auto& [f, svg] : paths.figures) files.push_back({f.file, svg});
  for (const auto& [name, content] : files) {
    if (auto s = write_whole(out / name, content); !s) return s.error();
    sum.files.push_back(name);
  }
  for (const auto& p : layout.plots)
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
