// What a reader gets: index.html self-contained (tables, inline SVG from
// gnuplot, no script, no external reference, unique ids), report.md with the
// same tables and links to the SVGs, trials.csv equal to `dtlab export`, the
// simulated-participant notice, a single participant; and every failure a
// clear Error with the right exit code, through the library and the CLI.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "analysis/report/report.h"
#include "study/store/export.h"
#include "study/store/store.h"
#include "tests/analysis/report/studies.h"

namespace dtlab::report::testing {
namespace {

namespace fs = std::filesystem;

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t i = text.find(needle); i != std::string::npos; i = text.find(needle, i + 1)) ++n;
  return n;
}

class ReportOutput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new TempDir;
    build_statsmodels_2x2(dir->file("s.sqlite"), /*simulated=*/true);
    auto r = write_report(dir->file("s.sqlite"), dir->file("out"));
    ASSERT_TRUE(r) << r.error().to_string();
    summary = new ReportSummary(*r);
    html = new std::string(read_text(dir->file("out/index.html")));
  }
  static void TearDownTestSuite() {
    delete html;
    delete summary;
    delete dir;
  }
  static TempDir* dir;
  static ReportSummary* summary;
  static std::string* html;
};
TempDir* ReportOutput::dir = nullptr;
ReportSummary* ReportOutput::summary = nullptr;
std::string* ReportOutput::html = nullptr;

TEST_F(ReportOutput, HtmlIsSelfContainedWithTablesAndInlineSvg) {
  EXPECT_EQ(html->rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_GE(count(*html, "<table>"), 8u);
  EXPECT_GE(count(*html, "<svg"), 5u);  // time bars, participants, speed-accuracy, ratings, position
  EXPECT_EQ(count(*html, "<?xml"), 0u);
  for (const char* banned : {"<script", "<link", "<img", "<iframe", "src=", "http://", "https://", "url(http", "@import"})
    EXPECT_EQ(count(*html, banned), 0u) << banned;
  // Every id once, every #reference to an id of the page.
  std::set<std::string> ids;
  const std::regex id_re("\\sid=[\"']([^\"']+)[\"']");
  for (auto it = std::sregex_iterator(html->begin(), html->end(), id_re); it != std::sregex_iterator(); ++it)
    EXPECT_TRUE(ids.insert((*it)[1]).second) << "duplicate id " << (*it)[1];
  const std::regex ref_re("(?:href=[\"']#|url\\(#)([^\"')]+)");
  for (auto it = std::sregex_iterator(html->begin(), html->end(), ref_re); it != std::sregex_iterator(); ++it)
    EXPECT_TRUE(ids.count((*it)[1])) << "dangling reference #" << (*it)[1];
}

TEST_F(ReportOutput, HtmlReadsLikeAResultsSection) {
  for (const char* text : {"Completion time", "Standard (off)", "DynTrans (on)",
                           "T1 (count targets)", "F(1, 7)", "Sphericity holds trivially", "Method of analysis",
                           "listwise deletion", "Speed and accuracy", "Frame-time audit", "Questionnaire",
                           "Position effects", "Simulated participants", "article (Table III, VII.1)",
                           // APA tables: Mauchly and both epsilons of the 4-level block position, GG-corrected df
                           "Mauchly's W", "ε GG", "ε HF", "MSE", "ηp² 90% CI", "ηG²", "(GG)", "In the text (APA style"})
    EXPECT_NE(html->find(text), std::string::npos) << text;
  EXPECT_TRUE(summary->simulated);
}

TEST_F(ReportOutput, MarkdownHasTheTablesAndLinksTheFigures) {
  const std::string md = read_text(dir->file("out/report.md"));
  EXPECT_NE(md.find("| T1 | "), std::string::npos);
  EXPECT_NE(md.find("Tasks: T1 count targets (abstract); T2 identify letter (abstract)"), std::string::npos);
  for (const auto& f : summary->files)
    if (f.rfind("figures/", 0) == 0) {
      EXPECT_NE(md.find("](" + f + ")"), std::string::npos) << f;
      EXPECT_TRUE(fs::exists(dir->file("out/" + f))) << f;
    }
  EXPECT_TRUE(fs::exists(dir->file("out/figures/report.gp")));
}

// report.tex holds the same tables and figures as index.html; with pdflatex on PATH (Debian:
// texlive-latex-recommended, texlive-fonts-recommended) it must compile, else only its structure is checked.
TEST_F(ReportOutput, LatexHasEveryTableAndFigureAndCompiles) {
  const std::string tex = read_text(dir->file("out/report.tex"));
  EXPECT_EQ(count(tex, "\\begin{table}") + count(tex, "\\begin{longtable}"), count(*html, "<table>"));
  EXPECT_EQ(count(tex, "\\toprule"), count(tex, "\\bottomrule"));
  EXPECT_EQ(count(tex, "\\includegraphics"), count(*html, "<svg"));
  for (const auto& f : summary->files)
    if (f.size() > 4 && f.compare(f.size() - 4, 4, ".pdf") == 0) {
      EXPECT_NE(tex.find("{" + f + "}"), std::string::npos) << f;
      EXPECT_GT(fs::file_size(dir->file("out/" + f)), 0u) << f;
    }
  if (std::system("pdflatex --version > /dev/null 2>&1") != 0) {
    std::cout << "[ NOTE     ] pdflatex is not installed: report.tex checked for structure only\n";
    return;
  }
  const std::string cmd = "cd '" + dir->file("out") + "' && pdflatex -interaction=nonstopmode -halt-on-error "
                          "report.tex > pdflatex.out 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(dir->file("out/pdflatex.out"));
  EXPECT_TRUE(fs::exists(dir->file("out/report.pdf")));
}

// trials.csv is the tidy table of every recorded trial: checked against the fixture's inputs (the
// statsmodels data placed as completion times), not against our own export.
TEST_F(ReportOutput, TidyCsvHoldsEveryRecordedTrialWithItsTime) {
  const std::string csv = read_text(dir->file("out/trials.csv"));
  std::istringstream lines(csv);
  std::string header, line;
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("participant,enrollment_index,session,session_status,order_row,position,block,transparency,"
                         "scenario,task,trial,",
                         0),
            0u)
      << header;
  std::vector<std::string> names;
  for (std::istringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  auto col = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) - names.begin(); };
  // statsmodels' anova-rm data: id, A, B, D, DV (tests/analysis/data/statsmodels_anova_rm.csv).
  std::map<std::string, double> dv;
  std::istringstream data(read_text(std::string(DTLAB_SOURCE_DIR) + "/tests/analysis/data/statsmodels_anova_rm.csv"));
  std::getline(data, line);
  std::vector<std::string> dv_names;
  for (std::istringstream h(line); std::getline(h, line, ',');) dv_names.push_back(line);
  for (std::string row; std::getline(data, row);) {
    std::vector<std::string> f;
    for (std::istringstream r(row); std::getline(r, line, ',');) f.push_back(line);
    std::map<std::string, std::string> m;
    for (size_t i = 0; i < f.size() && i < dv_names.size(); ++i) m[dv_names[i]] = f[i];
    dv[m["id"] + m["A"] + m["B"] + m["D"]] = std::stod(m["DV"]);
  }
  int rows = 0;
  for (std::string row; std::getline(lines, row); ++rows) {
    std::vector<std::string> f;
    for (std::istringstream r(row); std::getline(r, line, ',');) f.push_back(line);
    ASSERT_EQ(f.size(), names.size()) << row;
    const std::string key = f[col("participant")].substr(1) + (f[col("transparency")] == "off" ? "a" : "b") +
                            std::string(1, static_cast<char>('a' + std::stoi(f[col("trial")]) - 1)) +
                            (f[col("scenario")] == "abstract" ? "a" : "b");
    ASSERT_TRUE(dv.count(key)) << key;
    EXPECT_EQ(std::stod(f[col("completion_time_s")]), dv.at(key)) << row;
    EXPECT_EQ(f[col("excluded")], "NA");
  }
  EXPECT_EQ(rows, 8 * 24);  // 8 participants x 24 planned trials, all recorded
  for (const char* f : {"tests.csv", "completion_time_means.csv", "accuracy_means.csv", "questionnaire.csv",
                        "frames.csv", "report.json"})
    EXPECT_TRUE(fs::exists(dir->file(std::string("out/") + f))) << f;
  // tests.csv: one row per effect / Friedman test; the overall transparency row is there.
  const std::string tests = read_text(dir->file("out/tests.csv"));
  EXPECT_NE(tests.find("time,completion time,s,overall,rm-anova,transparency,8,1,7,"), std::string::npos);
}

// The same study run by people (the fixture's participants are simulated, whose frames confound nothing).
TEST(ReportFrames, FrameAuditCountsSlowTrialsAndFlagsConditionsBelowTheDisplayRate) {
  TempDir people;
  build_statsmodels_2x2(people.file("s.sqlite"));
  const auto j = run_report(people.file("s.sqlite"), people.file("out"));
  const auto* dir = &people;
  // Fixture frames: off {10, 12, 11} ms (p95 12), on {25, 30, 40} ms (p95 40 > 33.3): every "on" trial is slow.
  for (const auto& c : j.at("frames").at("conditions")) {
    const bool on = c.at("condition").get<std::string>().rfind("on/", 0) == 0;
    EXPECT_EQ(c.at("trials"), 48);
    EXPECT_EQ(c.at("slow_trials"), on ? 48 : 0);
    EXPECT_DOUBLE_EQ(c.at("median_p95_ms").get<double>(), on ? 40.0 : 12.0);
    // On a 60 Hz display (16.7 ms a frame): off's steady frames {12, 11} keep up, on's {30, 40}
    // (median 35 ms) do not, and both are later than 1.5 intervals (25 ms) in each of 48 trials.
    EXPECT_DOUBLE_EQ(c.at("display_hz").get<double>(), 60.0);
    EXPECT_DOUBLE_EQ(c.at("median_steady_ms").get<double>(), on ? 35.0 : 11.5);
    EXPECT_EQ(c.at("late_frames"), on ? 96 : 0);
    EXPECT_EQ(c.at("below_display"), on);
  }
  EXPECT_EQ(j.at("frames").at("below_display").size(), 2u);  // the two "on" conditions
  // on: 1000 / 35 = 28.6 fps, below 30; off: 1000 / 11.5 = 87.0 fps, 3.0 times on's: both warned, at the top too.
  for (const auto& c : j.at("frames").at("conditions"))
    EXPECT_NEAR(c.at("median_fps").get<double>(),
                c.at("condition").get<std::string>().rfind("on/", 0) == 0 ? 1000 / 35.0 : 1000 / 11.5, 1e-9);
  const auto& warnings = j.at("frames").at("warnings");
  ASSERT_EQ(warnings.size(), 3u);  // two "on" conditions below 30 fps, and the spread
  EXPECT_NE(warnings[2].get<std::string>().find("differ by more than 25%"), std::string::npos);
  const std::string md = read_text(dir->file("out/report.md"));
  const size_t top = md.find("Render cost may confound completion time");
  ASSERT_NE(top, std::string::npos);
  EXPECT_LT(top, md.find("## Completion time"));  // in the data section, before any result
  EXPECT_NE(md.find("rendered at a median 28.6 fps, below 30 fps"), std::string::npos);
  EXPECT_EQ(md.find("stayed fluid"), std::string::npos);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A protocol without [reference_results] (protocols/pilot.toml, simulated): the report compares with no
// other study, names none, and its frame audit says what the 10 fps software frames are instead of
// warning of a render-cost confound no participant saw (it used to open the report with one).
TEST(ReportOtherProtocol, NamesNoOtherStudyAndLabelsSimulatedFramesWithoutAConfoundWarning) {
  TempDir dir;
  build_pilot_simulated(dir.file("s.sqlite"));
  const auto j = run_report(dir.file("s.sqlite"), dir.file("out"));
  for (const char* file : {"out/index.html", "out/report.md", "out/report.json", "out/report.tex"}) {
    std::string text = lower(read_text(dir.file(file)));
    if (text.rfind("\\documentclass[10pt]{article}", 0) == 0) text.erase(0, text.find('\n'));  // LaTeX's class
    for (const char* banned : {"article", "elmqvist", "table iii", "dyntrans", "cf. "})
      EXPECT_EQ(text.find(banned), std::string::npos) << file << ": " << banned;
  }
  EXPECT_TRUE(j.at("design").at("published_results").is_null());
  EXPECT_FALSE(j.at("design").at("reference_design").get<bool>());
  const std::string md = read_text(dir.file("out/report.md"));
  EXPECT_EQ(md.find("this study"), std::string::npos);  // no column group beside a published one
  // Frames: on {500, 100, 100} ms: warm-up 500 ms apart, then 10 fps; off 100 fps: 10 times as fast.
  for (const auto& c : j.at("frames").at("conditions")) {
    const bool on = c.at("condition").get<std::string>().rfind("on/", 0) == 0;
    EXPECT_DOUBLE_EQ(c.at("median_fps").get<double>(), on ? 10.0 : 100.0);
    EXPECT_DOUBLE_EQ(c.at("median_first_ms").get<double>(), on ? 500.0 : 30.0);
    EXPECT_EQ(c.at("display"), "headless 160 × 120");
    EXPECT_FALSE(c.at("display_hz_known").get<bool>());
    // Late against 60 Hz (25 ms): both steady frames of every on trial, none of off.
    EXPECT_DOUBLE_EQ(c.at("late_share").get<double>(), on ? 1.0 : 0.0);
  }
  EXPECT_EQ(md.find("Render cost may confound completion time"), std::string::npos);
  EXPECT_TRUE(j.at("frames").at("warnings").empty());
  EXPECT_EQ(md.find("below 30 fps"), std::string::npos);
  EXPECT_NE(md.find("rendered offscreen at 160 × 120 pixels, by a software rasterizer"), std::string::npos);
  EXPECT_NE(md.find("there is no participant's screen to check for a render-cost confound"), std::string::npos);
  EXPECT_EQ(md.find("stayed fluid"), std::string::npos);
  // Counts agree with their nouns: one trial per condition.
  EXPECT_NE(md.find("1 trial per condition"), std::string::npos);
  EXPECT_EQ(md.find("1 trials"), std::string::npos);
  EXPECT_EQ(md.find("1 participants"), std::string::npos);
}

TEST(ReportEdge, SingleParticipantGetsDescriptivesAndNoTest) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 1);
  const auto j = run_report(dir.file("s.sqlite"), dir.file("out"));
  const auto& t = find_test(j, "completion_time", "overall");
  EXPECT_EQ(t.at("n"), 1);
  EXPECT_TRUE(find_effect(t, "transparency").at("F").is_null());
  // Order row 0 starts with off/abstract: T1 at positions 1-3 (21, 22, 23 s), T2 at 4-6 (24, 25, 26 s);
  // the overall value is the mean of the task means: (22 + 25) / 2.
  EXPECT_EQ(t.at("cells")[0].at("cell"), "off/abstract");
  EXPECT_DOUBLE_EQ(t.at("cells")[0].at("mean").get<double>(), 23.5);
  bool warned = false;
  for (const auto& w : j.at("warnings")) warned = warned || w.get<std::string>().find("Only 1 participant") == 0;
  EXPECT_TRUE(warned);
}

TEST(ReportEdge, PositionTestsAndBalanceOfTheLatinSquare) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 8);
  const auto j = run_report(dir.file("s.sqlite"), dir.file("out"));
  // 8 participants over the 4 x 4 Latin square: every condition twice at every block position.
  EXPECT_TRUE(j.at("position").at("balanced").get<bool>());
  for (const auto& [cond, counts] : j.at("position").at("balance").items())
    EXPECT_EQ(counts, nlohmann::json({2, 2, 2, 2})) << cond;
  // Times rise by 1 s per position: relative time rises with block position, a strong effect.
  const auto& e = find_effect(j.at("position").at("block").at("test"), "block position");
  EXPECT_EQ(e.at("df1").get<double>(), 3);
  EXPECT_LT(e.at("p").get<double>(), 1e-6);
  // Order row as between factor: 4 rows of 2.
  EXPECT_EQ(find_effect(j.at("position").at("order_row"), "order_row").at("df1").get<double>(), 3);
}

// The walked-path figures: the report asks its path-figure function once per analysed participant
// and WALKTHROUGH task (T3, T4 of the reference protocol; never T1, T2) with exactly that task's
// analysed trials, writes what it returns under paths/, links each from a table, and leaves out
// the figures the function found no poses for.
TEST(ReportPaths, OneFigurePerParticipantAndWalkthroughTaskIsWrittenAndLinked) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 2);
  std::vector<std::string> asked;  // "participant task"
  ReportOptions options;
  options.path_figure = [&](store::StudyReader& reader, const std::string& participant,
                            const std::vector<int>& positions, const std::string& title) -> Result<PathDrawing> {
    const auto trials = reader.trials(participant);
    EXPECT_TRUE(trials);
    std::string task;
    std::vector<int> expected;
    for (const auto& t : *trials)
      if (t.planned.position == positions.front()) task = t.planned.task;
    for (const auto& t : *trials)
      if (t.planned.task == task && !t.planned.practice) expected.push_back(t.planned.position);
    EXPECT_EQ(positions, expected) << participant << " " << task;
    asked.push_back(participant + " " + task);
    if (asked.size() == 4) return PathDrawing{};  // the last participant's T4: no poses recorded
    PathDrawing d{"<svg xmlns=\"http://www.w3.org/2000/svg\"><text>" + title + "</text></svg>\n", {}};
    if (asked.size() == 2) d.left_out.push_back("trial 99: this build generates another scene");
    return d;
  };
  auto r = write_report(dir.file("s.sqlite"), dir.file("out"), {}, options);
  ASSERT_TRUE(r) << r.error().to_string();
  ASSERT_EQ(asked.size(), 4u);
  EXPECT_EQ(asked[0].substr(asked[0].size() - 2), "T3");
  EXPECT_EQ(asked[1].substr(asked[1].size() - 2), "T4");
  const std::string participant = asked[0].substr(0, asked[0].size() - 3);
  const std::string first = "paths/01-" + participant + "-T3.svg";
  const std::string text = read_text(dir.file("out/" + first));
  EXPECT_NE(text.find(participant + ", task T3: walked paths"), std::string::npos) << text;
  std::size_t svgs = 0;
  for (const auto& f : r->files) svgs += f.rfind("paths/", 0) == 0;
  EXPECT_EQ(svgs, 3u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("out/paths")), fs::directory_iterator()), 3);
  EXPECT_FALSE(fs::exists(dir.file("out/paths/02-" + asked[3].substr(0, asked[3].size() - 3) + "-T4.svg")));
  const std::string html = read_text(dir.file("out/index.html"));
  EXPECT_EQ(count(html, "<a href=\"paths/"), 3u);
  EXPECT_NE(html.find("<a href=\"" + first + "\">" + first + "</a>"), std::string::npos);
  const std::string md = read_text(dir.file("out/report.md"));
  EXPECT_NE(md.find("## Walked paths"), std::string::npos);
  EXPECT_EQ(count(md, "](paths/"), 3u);
  const auto j = nlohmann::json::parse(read_text(dir.file("out/report.json")));
  ASSERT_EQ(j.at("path_figures").size(), 3u);
  EXPECT_EQ(j.at("path_figures")[0].at("file"), first);
  EXPECT_GT(j.at("path_figures")[0].at("trials").get<int>(), 0);
  // A trial left out of a figure is said under the table and among the warnings.
  EXPECT_NE(md.find("Not drawn: 1 trial, e.g. " + participant + " trial 99: this build generates another scene."),
            std::string::npos);
  ASSERT_EQ(j.at("path_figures_left_out").size(), 1u);
  bool warned = false;
  for (const auto& w : r->warnings) warned = warned || w.find("walked paths: 1 trial not drawn") == 0;
  EXPECT_TRUE(warned);
}

TEST(ReportPaths, NoFunctionNoSectionAndItsErrorsStopTheReport) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 2);
  auto plain = write_report(dir.file("s.sqlite"), dir.file("plain"));
  ASSERT_TRUE(plain) << plain.error().to_string();
  EXPECT_EQ(read_text(dir.file("plain/report.md")).find("Walked paths"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("plain/paths")));
  ReportOptions options;
  options.path_figure = [](store::StudyReader& reader, const std::string&, const std::vector<int>&,
                           const std::string&) -> Result<PathDrawing> {
    return Error{reader.path(), 0, 0, "sqlite", "disk I/O error", ErrorKind::environment};
  };
  auto r = write_report(dir.file("s.sqlite"), dir.file("out"), {}, options);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::environment);
  EXPECT_NE(r.error().to_string().find("disk I/O error"), std::string::npos);
}

TEST(ReportErrors, NotADatabaseIsAnInputError) {
  TempDir dir;
  std::ofstream(dir.file("x.sqlite")) << "hello, not a database\n";
  auto r = write_report(dir.file("x.sqlite"), dir.file("out"));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_input);
  EXPECT_NE(r.error().message.find("not an SQLite database"), std::string::npos) << r.error().to_string();
  EXPECT_FALSE(fs::exists(dir.file("out/index.html")));
}

TEST(ReportErrors, DatabaseWithoutTrialsIsAnInputError) {
  TempDir dir;
  StudySpec s;
  s.protocol_text = source_file("protocols/elmqvist2008.toml");
  s.participants = {"P1"};
  s.trial = [](size_t, const design::PlannedTrial&) -> std::optional<Outcome> { return std::nullopt; };
  build_study(dir.file("s.sqlite"), s);
  auto r = write_report(dir.file("s.sqlite"), dir.file("out"));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_input);
  EXPECT_NE(r.error().message.find("no recorded trial"), std::string::npos) << r.error().to_string();
}

TEST(ReportErrors, UnwritableDirectoryAndMissingGnuplotAreEnvironmentErrors) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 2);
  std::ofstream(dir.file("file")) << "x";
  auto r = write_report(dir.file("s.sqlite"), dir.file("file/out"));  // a regular file as parent
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::environment) << r.error().to_string();
  ReportOptions o;
  o.gnuplot = dir.file("no-such-gnuplot");
  auto g = write_report(dir.file("s.sqlite"), dir.file("out"), {}, o);
  ASSERT_FALSE(g);
  EXPECT_EQ(g.error().kind, ErrorKind::environment);
  EXPECT_NE(g.error().message.find("gnuplot"), std::string::npos);
}

// The CLI as a user runs it: exit codes 0, 1, 3 and --json.
int run_cli(const std::string& args, std::string* out = nullptr) {
  const std::string cmd = std::string(DTLAB_BINARY) + " analyze " + args + " 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  std::string text;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) text.append(buf, n);
  const int status = pclose(p);
  if (out) *out = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ReportCli, ExitCodesAndJson) {
  TempDir dir;
  build_small_reference(dir.file("s.sqlite"), 2);
  std::string out;
  ASSERT_EQ(run_cli(dir.file("s.sqlite") + " --out " + dir.file("out") + " --json", &out), 0);
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j.at("participants"), 2);
  EXPECT_EQ(j.at("trials"), 48);
  // Reading checkpoints like a writer: no write-ahead log is left next to the database.
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.sqlite-wal")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.sqlite-shm")));
  std::ofstream(dir.file("text.txt")) << "not a database";
  EXPECT_EQ(run_cli(dir.file("text.txt") + " --out " + dir.file("o2")), 1);
  std::ifstream text(dir.file("text.txt"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(text), {}), "not a database");  // left as it was
  EXPECT_EQ(run_cli(dir.file("s.sqlite") + " --out " + dir.file("o3") + " --gnuplot " + dir.file("nope")), 3);
  EXPECT_EQ(run_cli(dir.file("missing.sqlite") + " --out " + dir.file("o4")), 2);  // CLI11: not an existing file
}

}  // namespace
}  // namespace dtlab::report::testing

namespace dtlab::report::testing {
namespace {

// Issue 9: an excluded participant leaves every test (the error df of a 1-df within effect is
// n - 1) and is listed with the reason; --with-excluded keeps them; the database is untouched.
TEST(ReportExclusions, AnExcludedParticipantLeavesTheTestsAndIsListedWithTheReason) {
  TempDir dir;
  build_statsmodels_2x2(dir.file("s.sqlite"));
  {
    auto s = store::Store::open_existing(dir.file("s.sqlite"));
    ASSERT_TRUE(s) << s.error().to_string();
    ASSERT_TRUE(s->exclude("S8", std::nullopt, "misunderstood the task (counted blue objects)", "RA"));
    ASSERT_TRUE(s->exclude("S1", 5, "fire alarm during the trial", "RA"));
  }
  const auto j = run_report(dir.file("s.sqlite"), dir.file("out"));
  const auto& t = find_test(j, "completion_time", "overall");
  EXPECT_EQ(find_effect(t, "transparency").at("df2").get<double>(), 6);  // 7 participants kept
  EXPECT_EQ(j.at("summary").at("participants"), 7);
  EXPECT_EQ(j.at("summary").at("excluded_trials"), 24 + 1);  // S8's 24 and S1's fifth
  ASSERT_EQ(j.at("exclusions").size(), 2u);
  EXPECT_EQ(j.at("exclusions")[0].at("reason"), "misunderstood the task (counted blue objects)");
  const std::string html = read_text(dir.file("out/index.html"));
  EXPECT_NE(html.find("misunderstood the task (counted blue objects)"), std::string::npos);
  EXPECT_NE(html.find("fire alarm during the trial"), std::string::npos);

  ReportOptions keep;
  keep.with_excluded = true;
  auto r = write_report(dir.file("s.sqlite"), dir.file("kept"), {}, keep);
  ASSERT_TRUE(r) << r.error().to_string();
  EXPECT_EQ(r->participants, 8);
  const auto k = nlohmann::json::parse(read_text(dir.file("kept/report.json")));
  EXPECT_EQ(find_effect(find_test(k, "completion_time", "overall"), "transparency")
                .at("df2")
                .get<double>(),
            7);
}

// A withdrawn participant (dtlab withdraw) is in no analysis, even with --with-excluded, and the
// Participants section says how many withdrew and who; pauses and notes reach the report and its CSV.
TEST(ReportWithdrawal, AWithdrawnParticipantIsLeftOutAndCounted) {
  TempDir dir;
  build_statsmodels_2x2(dir.file("s.sqlite"));
  {
    auto s = store::Store::open_existing(dir.file("s.sqlite"));
    ASSERT_TRUE(s) << s.error().to_string();
    ASSERT_TRUE(s->withdraw("S8", "withdrew consent", "RA"));
    ASSERT_TRUE(s->add_note("S2", std::nullopt, "RA", "wore glasses"));
    ASSERT_TRUE(s->add_note("", std::nullopt, "RA", "the lab was warm all week"));
  }
  for (bool with_excluded : {false, true}) {
    ReportOptions options;
    options.with_excluded = with_excluded;
    const std::string out = dir.file(with_excluded ? "kept" : "out");
    auto r = write_report(dir.file("s.sqlite"), out, {}, options);
    ASSERT_TRUE(r) << r.error().to_string();
    EXPECT_EQ(r->participants, 7);
    const auto j = nlohmann::json::parse(read_text(out + "/report.json"));
    EXPECT_EQ(find_effect(find_test(j, "completion_time", "overall"), "transparency").at("df2").get<double>(), 6);
    const auto& p = j.at("sample");
    EXPECT_EQ(p.at("withdrawn"), nlohmann::json::array({"S8"}));
    EXPECT_EQ(p.at("described"), 7);
    ASSERT_EQ(p.at("around_sessions").size(), 1u);
    EXPECT_EQ(p.at("around_sessions")[0].at("participant"), "S2");
    EXPECT_EQ(p.at("around_sessions")[0].at("notes"), nlohmann::json::array({"wore glasses (RA)"}));
    EXPECT_EQ(p.at("study_notes"), nlohmann::json::array({"the lab was warm all week (RA)"}));
    const std::string md = read_text(out + "/report.md");
    EXPECT_NE(md.find("1 participant withdrew consent"), std::string::npos);
    EXPECT_NE(md.find("left out of every analysis: S8."), std::string::npos);
    EXPECT_NE(read_text(out + "/sessions_notes.csv").find("S2,0,0,wore glasses (RA)"), std::string::npos);
  }
}

// Text typed by the experimenter reaches every format as text, never as markup. Regression:
// report.md wrote an exclusion reason's <script> as raw HTML (index.html and report.tex escaped it).
TEST(ReportExclusions, ReasonsWithMarkupAreTextInEveryFormat) {
  TempDir dir;
  build_statsmodels_2x2(dir.file("s.sqlite"));
  const std::string reason = "<script>alert(1)</script> & a lone ` tick *then* <b>bold</b> &amp; <!-- c -->";
  {
    auto s = store::Store::open_existing(dir.file("s.sqlite"));
    ASSERT_TRUE(s) << s.error().to_string();
    ASSERT_TRUE(s->exclude("S8", std::nullopt, reason, "RA"));
  }
  run_report(dir.file("s.sqlite"), dir.file("out"));
  const std::string md = read_text(dir.file("out/report.md"));
  for (const char* raw : {"<script>", "</script>", "<b>", "<!--"}) EXPECT_EQ(md.find(raw), std::string::npos) << raw;
  EXPECT_NE(md.find("&lt;script>alert(1)&lt;/script> & a lone \\` tick \\*then\\* &lt;b>bold&lt;/b> &amp;amp; &lt;!-- c -->"),
            std::string::npos)
      << "the reason, escaped once for Markdown";
  const std::string html = read_text(dir.file("out/index.html"));
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
}

// Issue 9: a comment added to the protocol mid-study (same design) changes nothing in the
// analysis: participants of both texts are pooled, the statistics equal a study recorded under
// one text. A changed design (allowed) gets a report per design revision.
TEST(ReportRevisions, ARewordedProtocolPoolsAndAChangedDesignIsAnalysedSeparately) {
  TempDir dir;
  const std::string text = source_file("protocols/elmqvist2008.toml");
  const std::vector<std::string> first{"P1", "P2", "P3", "P4"}, second{"P5", "P6", "P7", "P8"};
  build_reference_participants(dir.file("one.sqlite"), first, text);
  build_reference_participants(dir.file("one.sqlite"), second, text);
  build_reference_participants(dir.file("two.sqlite"), first, text);
  build_reference_participants(dir.file("two.sqlite"), second, text + "\n# a comment added mid-study\n");
  const auto a = run_report(dir.file("one.sqlite"), dir.file("a"));
  const auto b = run_report(dir.file("two.sqlite"), dir.file("b"));
  EXPECT_EQ(b.at("summary").at("participants"), 8);
  const auto& ea = find_effect(find_test(a, "completion_time", "overall"), "transparency");
  const auto& eb = find_effect(find_test(b, "completion_time", "overall"), "transparency");
  EXPECT_EQ(ea.at("F"), eb.at("F"));
  EXPECT_EQ(ea.at("p"), eb.at("p"));
  EXPECT_EQ(b.at("protocol").at("design_revisions"), 1);
  EXPECT_EQ(b.at("protocol").at("protocol_texts"), 2);

  std::string redesigned = text;
  const auto at = redesigned.find("master_seed = ");
  ASSERT_NE(at, std::string::npos);
  redesigned.insert(at + std::string("master_seed = ").size(), "9");
  build_reference_participants(dir.file("two.sqlite"), {"Q1", "Q2", "Q3"}, redesigned, /*allow_change=*/true);
  auto all = write_report(dir.file("two.sqlite"), dir.file("c"));
  ASSERT_TRUE(all) << all.error().to_string();
  EXPECT_EQ(all->revisions, (std::vector<int>{1, 2}));
  EXPECT_TRUE(fs::exists(dir.file("c/revision-1/index.html")));
  EXPECT_TRUE(fs::exists(dir.file("c/revision-2/index.html")));
  const std::string top = read_text(dir.file("c/index.html"));
  EXPECT_NE(top.find("analysed separately"), std::string::npos);
  const auto r1 = nlohmann::json::parse(read_text(dir.file("c/revision-1/report.json")));
  const auto r2 = nlohmann::json::parse(read_text(dir.file("c/revision-2/report.json")));
  EXPECT_EQ(r1.at("summary").at("participants"), 8);
  EXPECT_EQ(r2.at("summary").at("participants"), 3);
  ReportOptions latest;
  latest.revision = "latest";
  auto l = write_report(dir.file("two.sqlite"), dir.file("d"), {}, latest);
  ASSERT_TRUE(l);
  EXPECT_EQ(l->participants, 3);
  latest.revision = "7";
  auto none = write_report(dir.file("two.sqlite"), dir.file("e"), {}, latest);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().kind, ErrorKind::not_found);
}

}  // namespace
}  // namespace dtlab::report::testing
