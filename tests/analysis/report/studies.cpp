// The shared test studies; see studies.h. Data files are read from
// tests/analysis/data (provenance: tests/analysis/data/PROVENANCE.md).
#include "tests/analysis/report/studies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "analysis/stats/csv.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"

namespace dtlab::report::testing {
namespace {

stats::CsvTable read_csv(const std::string& relative) {
  auto t = stats::read_csv_file(std::string(DTLAB_SOURCE_DIR) + "/" + relative);
  if (!t) throw std::runtime_error(t.error().to_string());
  return std::move(*t);
}

// statsmodels anova-rm data: (id, A, B, D) -> DV.
std::map<std::tuple<std::string, std::string, std::string, std::string>, double> statsmodels_data() {
  const auto t = read_csv("tests/analysis/data/statsmodels_anova_rm.csv");
  const int id = t.column("id"), a = t.column("A"), b = t.column("B"), d = t.column("D"), dv = t.column("DV");
  std::map<std::tuple<std::string, std::string, std::string, std::string>, double> out;
  for (const auto& r : t.rows)
    out[{r[static_cast<size_t>(id)], r[static_cast<size_t>(a)], r[static_cast<size_t>(b)], r[static_cast<size_t>(d)]}] =
        std::stod(r[static_cast<size_t>(dv)]);
  return out;
}

// Answers of the reference tasks that make every error measure non-trivial (see the tests for the values).
void reference_answers(size_t p, const design::PlannedTrial& t, Outcome& o) {
  const bool off = level(t, "transparency") == "off";
  const int k = t.trial;
  if (t.task == "T1") {
    const int truth = 20 + 5 * k;  // 25, 30, 35
    int answer = truth;
    if (off) answer += k == 1 ? 1 + static_cast<int>(p % 2) : k == 3 ? -1 : 0;
    else if (p % 2 == 1 && k == 2) answer += 1;
    o.truth = store::Count{truth};
    o.answer = store::Count{answer};
  } else if (t.task == "T2") {
    o.truth = store::Letter{"K"};
    o.answer = store::Letter{off && k == 3 && p < 4 ? "X" : "K"};
  } else if (t.task == "T3") {
    o.truth = store::Position{10, 10};
    o.answer = off ? store::Position{13, 14} : store::Position{10 + 0.5 * static_cast<double>(p), 10};
  } else {
    const int truth = 4 + k;
    o.truth = store::Count{truth};
    o.answer = store::Count{off && k == 1 ? truth - 1 - static_cast<int>(p % 3) : truth};
  }
  o.frame_ms = off ? std::vector<double>{10, 12, 11} : std::vector<double>{25, 30, 40};
}

std::vector<store::QuestionnaireAnswer> reference_questionnaire(size_t p) {
  return {
      {"rating", "scenario=abstract;transparency=off", 1.0},
      {"rating", "scenario=abstract;transparency=on", 3.0},
      {"rating", "scenario=walkthrough;transparency=off", 2.0},
      {"rating", "scenario=walkthrough;transparency=on", p < 6 ? 3.0 : 1.0},
      {"preference", "", std::string(p < 7 ? "on" : "neutral")},
      {"depth_self", "", p % 2 ? 3.0 : 2.0},
      {"depth_test", "", p == 3 ? 2.0 : 3.0},
  };
}

}  // namespace

void build_statsmodels_2x2(const std::string& path, bool simulated) {
  const auto dv = statsmodels_data();
  StudySpec s;
  s.protocol_text = source_file("protocols/elmqvist2008.toml");
  for (int i = 1; i <= 8; ++i) s.participants.push_back("S" + std::to_string(i));
  if (simulated) s.demographics = [](size_t) { return store::Demographics{{"simulated", "true"}}; };
  s.trial = [&dv](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    const std::string a = level(t, "transparency") == "off" ? "a" : "b";
    const std::string d = level(t, "scenario") == "abstract" ? "a" : "b";
    const std::string b(1, static_cast<char>('a' + t.trial - 1));
    o.time_s = dv.at({std::to_string(p + 1), a, b, d});
    reference_answers(p, t, o);
    return o;
  };
  s.questionnaire = reference_questionnaire;
  build_study(path, s);
}

void build_statsmodels_t1(const std::string& path) {
  const auto dv = statsmodels_data();
  StudySpec s;
  s.protocol_text = source_file("protocols/elmqvist2008.toml");
  for (int i = 1; i <= 8; ++i) s.participants.push_back("S" + std::to_string(i));
  s.trial = [&dv](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    const bool off = level(t, "transparency") == "off";
    o.time_s = t.task == "T1" ? dv.at({std::to_string(p + 1), "a", off ? "a" : "b", "a"})
                              : 30.0 + static_cast<double>(p) + (off ? 0.0 : 0.5 * static_cast<double>(p % 3));
    reference_answers(p, t, o);
    return o;
  };
  build_study(path, s);
}

void build_pingouin_wide(const std::string& path) {
  const auto t = read_csv("tests/analysis/data/pingouin_rm_anova_wide.csv");  // Before,1 week,2 week,3 week
  StudySpec s;
  s.protocol_text = R"(format = 1
id = "oneway4"
title = "One factor, four levels"
participants = 12
master_seed = 7
[factors.week]
levels = ["before", "week1", "week2", "week3"]
[order]
scheme = "latin-square"
[scenarios.abstract]
kind = "abstract"
[scenarios.abstract.tasks.T1]
type = "count-targets"
trials = 1
[rendering.plain]
method = "standard"
)";
  // Subjects (1-based rows of the file) in enrollment order: index k gets Latin-square row k mod 4,
  // row 0 = (before, week1, week2, week3), row 1 = (week1, week2, week3, before). Subjects 3 and 7
  // lack their last cells in row 0's order, subject 11 lacks "before", last in row 1.
  const std::vector<int> order = {3, 11, 1, 2, 7, 4, 5, 6, 8, 9, 10, 12};
  for (int subject : order) s.participants.push_back("W" + std::string(subject < 10 ? "0" : "") + std::to_string(subject));
  const std::vector<std::string> levels = {"before", "week1", "week2", "week3"};
  s.trial = [t, order, levels](size_t p, const design::PlannedTrial& tr) -> std::optional<Outcome> {
    const auto& row = t.rows[static_cast<size_t>(order[p] - 1)];
    const size_t col = static_cast<size_t>(std::find(levels.begin(), levels.end(), level(tr, "week")) - levels.begin());
    if (row[col].empty()) return std::nullopt;  // the session stops before its missing cells
    Outcome o;
    o.time_s = std::stod(row[col]);
    o.truth = store::Count{10};
    o.answer = store::Count{10};
    return o;
  };
  build_study(path, s);
}

void build_pingouin_months(const std::string& path) {
  const auto t = read_csv("tests/analysis/data/pingouin_mixed_anova.csv");  // Scores,Time,Group,Subject
  std::map<std::pair<std::string, std::string>, double> score;
  for (const auto& r : t.rows) {
    std::string month = r[1];
    month[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(month[0])));
    score[{r[3], month}] = std::stod(r[0]);
  }
  // R: friedman.test(RoundingTimes) example data (Hollander & Wolfe 1973), 22 x 3.
  static const double kRounding[22][3] = {
      {5.40, 5.50, 5.55}, {5.85, 5.70, 5.75}, {5.20, 5.60, 5.50}, {5.55, 5.50, 5.40}, {5.90, 5.85, 5.70},
      {5.45, 5.55, 5.60}, {5.40, 5.40, 5.35}, {5.45, 5.50, 5.35}, {5.25, 5.15, 5.00}, {5.85, 5.80, 5.70},
      {5.25, 5.20, 5.10}, {5.65, 5.55, 5.45}, {5.60, 5.35, 5.45}, {5.05, 5.00, 4.95}, {5.50, 5.50, 5.40},
      {5.45, 5.55, 5.50}, {5.55, 5.55, 5.35}, {5.45, 5.50, 5.55}, {5.50, 5.45, 5.25}, {5.65, 5.60, 5.40},
      {5.70, 5.65, 5.55}, {6.30, 6.30, 6.25}};
  StudySpec s;
  s.protocol_text = R"(format = 1
id = "months3"
title = "One factor, three levels"
participants = 60
master_seed = 11
[factors.month]
levels = ["august", "january", "june"]
[order]
scheme = "latin-square"
[scenarios.abstract]
kind = "abstract"
[scenarios.abstract.tasks.T1]
type = "count-targets"
trials = 1
[rendering.plain]
method = "standard"
[questionnaire.speed]
type = "rating"
prompt = "How fast were you?"
scale = [0, 10]
per = ["month"]
)";
  for (int i = 0; i < 60; ++i) s.participants.push_back("M" + std::string(i < 10 ? "0" : "") + std::to_string(i));
  s.trial = [score](size_t p, const design::PlannedTrial& tr) -> std::optional<Outcome> {
    Outcome o;
    o.time_s = score.at({std::to_string(p), level(tr, "month")});
    o.truth = store::Count{10};
    o.answer = store::Count{10};
    return o;
  };
  s.questionnaire = [](size_t p) {
    std::vector<store::QuestionnaireAnswer> a;
    if (p < 22)
      for (int m = 0; m < 3; ++m)
        a.push_back({"speed", std::string("month=") + (m == 0 ? "august" : m == 1 ? "january" : "june"), kRounding[p][m]});
    return a;
  };
  build_study(path, s);
}

void build_reference_participants(const std::string& path, const std::vector<std::string>& ids,
                                  const std::string& protocol_text, bool allow_change) {
  StudySpec s;
  s.protocol_text = protocol_text;
  s.participants = ids;
  s.allow_protocol_change = allow_change;
  s.trial = [](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    o.time_s = 20.0 + t.position + static_cast<double>(p) + (level(t, "transparency") == "on" ? 0.0 : 3.0 * (p % 3));
    reference_answers(p, t, o);
    return o;
  };
  build_study(path, s);
}

void build_small_reference(const std::string& path, int n) {
  StudySpec s;
  s.protocol_text = source_file("protocols/elmqvist2008.toml");
  for (int i = 1; i <= n; ++i) s.participants.push_back("P" + std::to_string(i));
  s.trial = [](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    o.time_s = 20.0 + t.position + static_cast<double>(p);
    reference_answers(p, t, o);
    return o;
  };
  build_study(path, s);
}

void build_pilot_simulated(const std::string& path) {
  StudySpec s;
  s.protocol_text = source_file("protocols/pilot.toml");
  for (int i = 1; i <= 4; ++i) s.participants.push_back("P" + std::to_string(i));
  s.demographics = [](size_t) { return store::Demographics{{"simulated", "true"}}; };
  s.display = store::DisplayInfo{"headless", 160, 120, std::nullopt,
                                 "4.5 (Core Profile) Mesa 22.3.6 / llvmpipe (LLVM 15.0.6, 256 bits)", ""};
  s.trial = [](size_t p, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    const bool off = level(t, "transparency") == "off";
    o.time_s = 20.0 + t.position + (off ? 5.0 : 0.0);
    reference_answers(p, t, o);
    o.frame_ms = off ? std::vector<double>{30, 10, 10} : std::vector<double>{500, 100, 100};
    return o;
  };
  s.questionnaire = reference_questionnaire;
  build_study(path, s);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json run_report(const std::string& db, const std::string& out, const ReportOptions& options) {
  auto r = write_report(db, out, {}, options);
  if (!r) {
    ADD_FAILURE() << r.error().to_string();
    throw std::runtime_error("write_report failed");
  }
  return nlohmann::json::parse(read_text(out + "/report.json"));
}

void build_instruments(const std::string& path) {
  StudySpec s;
  s.protocol_text = source_file("protocols/pilot.toml") + R"(
[questionnaire.tlx]
instrument = "nasa-tlx"
when = "block"

[questionnaire.ease]
type = "likert"
prompt = "The view was easy to use."
points = 7
labels = ["Strongly disagree", "Strongly agree"]
when = "level:transparency"

[questionnaire.comment]
type = "text"
prompt = "Anything else?"
)";
  for (int i = 1; i <= 8; ++i) s.participants.push_back("P" + std::to_string(i));
  s.trial = [](size_t, const design::PlannedTrial& t) -> std::optional<Outcome> {
    Outcome o;
    o.time_s = 20 + t.position;
    return o;
  };
  const auto tlx = read_csv("tests/analysis/data/instruments_tlx.csv");
  const auto ease = read_csv("tests/analysis/data/instruments_ease.csv");
  auto proto = protocol::load_protocol_text(s.protocol_text, "instruments.toml");
  if (!proto) throw std::runtime_error(proto.error().to_string());
  s.questionnaire = [tlx, ease, p = proto.value()](size_t i) {
    const std::string who = "P" + std::to_string(i + 1);
    // The ledger gives participant i order row i mod 4 (nobody released): its plan names the blocks.
    const design::Plan plan = design::make_plan(p, static_cast<int>(i), static_cast<int>(i % 4));
    std::vector<store::QuestionnaireAnswer> a;
    const int pc = tlx.column("participant"), tc = tlx.column("transparency"), sc = tlx.column("scenario");
    for (const auto& r : tlx.rows) {
      if (r[static_cast<size_t>(pc)] != who) continue;
      int block = 0;
      for (const auto& t : plan.trials)
        if (level(t, "transparency") == r[static_cast<size_t>(tc)] && level(t, "scenario") == r[static_cast<size_t>(sc)])
          block = t.block;
      for (const char* d : {"mental", "physical", "temporal", "performance", "effort", "frustration"})
        a.push_back({std::string("tlx.") + d, "block=" + std::to_string(block),
                     std::stod(r[static_cast<size_t>(tlx.column(d))])});
    }
    for (const auto& r : ease.rows)
      if (r[static_cast<size_t>(ease.column("participant"))] == who)
        a.push_back({"ease", "transparency=" + r[static_cast<size_t>(ease.column("transparency"))],
                     std::stod(r[static_cast<size_t>(ease.column("ease"))])});
    a.push_back({"comment", "", i % 3 == 0 ? "Participant " + who + " found the lens \"slow\"; für mich gut." : std::string()});
    return a;
  };
  build_study(path, s);
}

const nlohmann::json& find_test(const nlohmann::json& report, const std::string& section, const std::string& scope,
                                const std::string& measure) {
  for (const auto& t : report.at(section).at("tests"))
    if (t.at("scope") == scope && (measure.empty() || t.at("measure") == measure)) return t;
  ADD_FAILURE() << "no test " << section << " / " << scope << " / " << measure;
  throw std::runtime_error("test not found");
}

const nlohmann::json& find_effect(const nlohmann::json& test, const std::string& name) {
  for (const auto& e : test.at("effects"))
    if (e.at("effect") == name) return e;
  ADD_FAILURE() << "no effect " << name;
  throw std::runtime_error("effect not found");
}

}  // namespace dtlab::report::testing
