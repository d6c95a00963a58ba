// write_report: read, analyse, draw, write (report.h). The database is read
// twice, both times read-only: once through store::export_trials_csv (the
// tidy CSV, byte for byte what `dtlab export` writes, and the check that the
// file is a dtlab database) and once for the analysis. Output files are
// written to a temporary name and renamed, so each is whole or absent.
#include "analysis/report/report.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/report/detail/design.h"
#include "analysis/report/detail/document.h"
#include "analysis/report/detail/plots.h"
#include "analysis/report/detail/sections.h"
#include "analysis/report/detail/study_data.h"
#include "study/common/version.h"
#include "study/store/export.h"
#include "study/store/store.h"

namespace dtlab::report {
namespace {

namespace fs = std::filesystem;
using namespace detail;

Error output_error(const fs::path& p, const std::string& what) { return Error{p.string(), 0, 0, "output", what}; }

Status write_whole(const fs::path& p, const std::string& text) {
  const fs::path tmp = p.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return output_error(p, "cannot write the file (is the output directory writable?)");
    out << text;
    out.flush();
    if (!out) return output_error(p, "writing the file failed (disk full?)");
  }
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return output_error(p, "cannot move the file into place: " + ec.message());
  }
  return {};
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
  return {{"factors", f}, {"primary", d.factor(d.primary).name}, {"tasks", t}, {"reference_design", d.reference}};
}

}  // namespace

bool is_environment_error(const Error& e) { return e.field == "sqlite" || e.field == "output" || e.field == "gnuplot"; }

Result<ReportSummary> write_report(const std::string& db_path, const std::string& out_dir, const ProgressFn& progress,
                                   const ReportOptions& options) {
  auto say = [&](const std::string& step) {
    if (progress) progress(step);
  };
  const std::string gnuplot = gnuplot_executable(options.gnuplot);
  if (auto s = check_gnuplot(gnuplot); !s) return s.error();

  say("reading " + db_path);
  std::ostringstream tidy;
  auto exported = store::export_trials_csv(db_path, tidy);
  if (!exported) {
    Error e = exported.error();
    if (store::is_environment_error(e)) e.field = "sqlite";
    return e;
  }
  auto read = read_study(db_path);
  if (!read) return read.error();
  const StudyData& data = *read;
  const Design design = make_design(data.protocol);
  Context ctx(data, design, options);
  for (const auto& p : data.participants) {
    long long n = 0;
    for (const auto& t : data.trials) n += t.participant == p.id && ctx.analysed(t) ? 1 : 0;
    if (n) ctx.subjects.push_back(p.id);
    ctx.analysed_trials += n;
  }
  if (ctx.analysed_trials == 0)
    return Error{db_path, 0, 0, "trial_table",
                 "no recorded trial to analyse (" + std::to_string(data.participants.size()) +
                     " participants enrolled, " + std::to_string(data.trials.size()) +
                     " trials of the current protocol, practice trials excluded); run sessions first"};
  for (const auto& id : simulated_participants(data))
    if (std::find(ctx.subjects.begin(), ctx.subjects.end(), id) != ctx.subjects.end()) ctx.simulated.push_back(id);

  const fs::path out(out_dir), figures = out / "figures";
  std::error_code ec;
  fs::create_directories(figures, ec);
  if (ec || !fs::is_directory(figures))
    return output_error(out, "cannot create the output directory: " + (ec ? ec.message() : "not a directory"));

  say("participants and design (" + std::to_string(ctx.subjects.size()) + " participants, " +
      std::to_string(ctx.analysed_trials) + " trials)");
  section_overview(ctx);
  say("completion time");
  section_time(ctx);
  say("accuracy");
  section_errors(ctx);
  say("speed and accuracy");
  section_speed_accuracy(ctx);
  say("questionnaire");
  section_questionnaire(ctx);
  say("position effects");
  section_position(ctx);
  say("frame-time audit");
  section_frames(ctx);
  section_notes(ctx);

  say("drawing " + std::to_string(ctx.plots.size()) + " figures with " + gnuplot);
  auto svg = render_plots(ctx.plots, figures.string(), gnuplot);
  if (!svg) return svg.error();

  ReportSummary sum;
  sum.out_dir = out_dir;
  sum.participants = static_cast<int>(ctx.subjects.size());
  sum.trials = ctx.analysed_trials;
  sum.tests = ctx.tests;
  sum.simulated = !ctx.simulated.empty() && ctx.simulated.size() == ctx.subjects.size();
  sum.warnings = ctx.warnings;

  nlohmann::json& j = ctx.json;
  j["report_format"] = 1;
  j["generated_by"] = std::string(dtlab::version_string());
  j["generated_at"] = utc_now();
  j["database"] = db_path;
  j["protocol"] = {{"id", data.protocol.id}, {"title", data.protocol.title}, {"sha256", data.protocol.sha256},
                   {"software_version", data.software_version}};
  j["design"] = design_json(design);
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& p : data.participants) {
    const bool analysed = std::find(ctx.subjects.begin(), ctx.subjects.end(), p.id) != ctx.subjects.end();
    const bool sim = std::find(ctx.simulated.begin(), ctx.simulated.end(), p.id) != ctx.simulated.end();
    parts.push_back({{"id", p.id}, {"index", p.index}, {"order_row", p.order_row},
                     {"session", p.session_status.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.session_status)},
                     {"planned", p.planned}, {"recorded", p.recorded}, {"analysed", analysed}, {"simulated", sim}});
  }
  j["participants"] = parts;
  j["summary"] = {{"participants", sum.participants}, {"trials", sum.trials}, {"tests", sum.tests},
                  {"simulated", sum.simulated}, {"simulated_participants", ctx.simulated}};
  j["warnings"] = ctx.warnings;
  std::vector<std::string> figure_files;
  for (const auto& p : ctx.plots) figure_files.push_back("figures/" + p.id + ".svg");
  j["figures"] = figure_files;

  say("writing " + out_dir);
  std::vector<std::pair<std::string, std::string>> files = {
      {"trials.csv", tidy.str()},
      {"tests.csv", tests_csv(ctx)},
      {"report.json", j.dump(2) + "\n"},
      {"report.md", render_markdown(ctx.doc)},
      {"index.html", render_html(ctx.doc, *svg)},
  };
  for (const auto& [name, content] : ctx.csv) files.push_back({name, content});
  for (const auto& [name, content] : files) {
    if (auto s = write_whole(out / name, content); !s) return s.error();
    sum.files.push_back(name);
  }
  for (const auto& f : figure_files) sum.files.push_back(f);
  return sum;
}

}  // namespace dtlab::report
