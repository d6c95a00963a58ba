// The study databases the report tests share, each built from a data set
// whose analysis is published (R ez::ezANOVA via statsmodels' tests,
// JAMOVI/ezANOVA via pingouin's tests, R's friedman.test examples), placed as
// completion times so that the report's F and p can be checked against the
// published values; and helpers to run the report and read report.json.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "analysis/report/report.h"
#include "tests/analysis/report/fixture.h"

namespace dtlab::report::testing {

// The reference protocol (protocols/elmqvist2008.toml), 8 participants S1..S8:
// completion time of transparency t, scenario s, repetition k = statsmodels'
// anova-rm data DV at A = t (off a, on b), D = s (abstract a, walkthrough b),
// B = k (a, b, c), subject = participant. Both tasks of a scenario get the
// same times. Answers, ratings, preference and depth test: see studies.cpp.
void build_statsmodels_2x2(const std::string& path, bool simulated = false);

// The reference protocol, 8 participants: T1 times are statsmodels' rows 1-16
// (off = B a, on = B b, at A = a, D = a); the other tasks a constant 30 s.
void build_statsmodels_t1(const std::string& path);

// One factor `week` of four levels (role none), one count task with one
// trial: pingouin's rm_anova_wide data, 12 participants, three with missing
// cells (sessions stopped before them; the Latin square puts them last).
void build_pingouin_wide(const std::string& path);

// One factor `month` of three levels, 60 participants: pingouin's
// mixed_anova Scores by Time; the first 22 participants rate the months with
// R's RoundingTimes values (friedman.test example).
void build_pingouin_months(const std::string& path);

// The reference protocol, `n` participants, every trial 20 + position seconds, no questionnaire.
void build_small_reference(const std::string& path, int n);
// The same for participants `ids` under `protocol_text` (a variant of the reference protocol), into
// an existing database too; `allow_change` records a changed design beside the old one.
void build_reference_participants(const std::string& path, const std::vector<std::string>& ids,
                                  const std::string& protocol_text, bool allow_change = false);

// protocols/pilot.toml (no published results), participants P1..P4 marked simulated, shown headless at
// 160 x 120 by a software renderer (llvmpipe) of unknown rate: off frames {30, 10, 10} ms, on frames
// {500, 100, 100} ms (a warm-up first frame, then 10 fps); times 20 + position s (+5 s off); answers and
// questionnaire as the reference study's fixtures.
void build_pilot_simulated(const std::string& path);
// protocols/pilot.toml with NASA-TLX after every block (`tlx`), a 7-point Likert item after each
// transparency level (`ease`) and a free-text comment at the end, 8 participants P1..P8: the answers
// of tests/analysis/data/instruments_tlx.csv and instruments_ease.csv (each TLX row stored under the
// block that ran its condition); P1, P4 and P7 write a comment, the others leave it empty.
void build_instruments(const std::string& path);
// Runs write_report into `out` (gnuplot from PATH); fails the test on error.
nlohmann::json run_report(const std::string& db, const std::string& out, const ReportOptions& options = {});

// The test of `section` ("completion_time", "accuracy") with this scope and measure ("" = any).
const nlohmann::json& find_test(const nlohmann::json& report, const std::string& section, const std::string& scope,
                                const std::string& measure = "");
// The effect named `name` of an ANOVA test.
const nlohmann::json& find_effect(const nlohmann::json& test, const std::string& name);

std::string read_text(const std::string& path);

}  // namespace dtlab::report::testing
