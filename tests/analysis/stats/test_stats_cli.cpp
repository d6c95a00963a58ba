// `dtlab stats` run as a user runs it: NIST StRD LRE through the CSV path and
// the JSON output, the JSON fields each test promises, warnings naming the
// removed subjects, and exit codes with file:line:column messages.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <string>
#include <sys/wait.h>

#include "test_util.h"
#include "tests/common/run_cli.h"

namespace dtlab::stats {
namespace {

using nlohmann::json;

using CliRun = dtlab::test::CliOutcome;

CliRun dtlab(const std::string& args) { return dtlab::test::run_dtlab(args); }

std::string data(const std::string& name) { return test::data_path(name); }

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

double number(const json& j) { return j.get<double>(); }

TEST(StatsCli, NistLreThroughTheCommandLine) {
  auto cert = read_csv_file(data("nist/certified.csv"));
  ASSERT_TRUE(cert.ok());
  for (const auto& row : cert->rows) {
    SCOPED_TRACE(row[0]);
    const CliRun r = dtlab("stats anova --data " + data("nist/" + row[0] + ".csv") + " --dv response --between treatment --json");
    ASSERT_EQ(r.rc, 0) << r.err;
    const json j = json::parse(r.out);
    const json& e = j["effects"][0];
    EXPECT_GE(test::lre(number(e["ss"]), std::strtod(row[2].c_str(), nullptr)), 12.0);
    EXPECT_GE(test::lre(number(e["ss_error"]), std::strtod(row[6].c_str(), nullptr)), 12.0);
    EXPECT_GE(test::lre(number(e["F"]), std::strtod(row[4].c_str(), nullptr)), 12.0);
  }
}

TEST(StatsCli, RmAnovaJsonHasEveryFieldPerEffect) {
  const CliRun r = dtlab("stats rm-anova --data " + data("md_12.1.csv") + " --dv rt --subject id --within angle,noise --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  const std::set<std::string> expected{"effect",     "df1",        "df2",        "ss",        "ss_error",
                                       "mse",        "F",          "p",          "log10_p",   "eta_p2",
                                       "eta_p2_ci90_low", "eta_p2_ci90_high", "eta_g2", "mauchly_W", "mauchly_p",
                                       "gg_epsilon", "hf_epsilon", "df1_gg",     "df2_gg",    "mse_gg",
                                       "p_gg",       "log10_p_gg", "df1_hf",     "df2_hf",    "mse_hf",
                                       "p_hf",       "log10_p_hf", "apa"};
  ASSERT_EQ(j["effects"].size(), 3u);
  for (const auto& e : j["effects"]) {
    std::set<std::string> keys;
    for (auto it = e.begin(); it != e.end(); ++it) keys.insert(it.key());
    EXPECT_EQ(keys, expected);
  }
  const json& angle = j["effects"][0];
  EXPECT_EQ(angle["effect"], "angle");
  // Maxwell & Delaney (2004) Table 12.1: SS 289920, error 64080; car: GG 0.961637, HF 1.217564
  EXPECT_NEAR(number(angle["ss"]), 289920, 1e-8);
  EXPECT_NEAR(number(angle["ss_error"]), 64080, 1e-8);
  EXPECT_TRUE(test::printed(number(angle["gg_epsilon"]), "0.961637"));
  EXPECT_TRUE(test::printed(number(angle["hf_epsilon"]), "1.217564"));
  EXPECT_TRUE(j["effects"][1]["mauchly_W"].is_null()) << "1-df effect: no Mauchly test";
  // Maxwell & Delaney: noise F(1, 9) = 33.77, MSE = 76140 / 9
  EXPECT_EQ(j["effects"][1]["apa"].get<std::string>().substr(0, 16), "F(1, 9) = 33.77,");
  EXPECT_NEAR(number(j["effects"][1]["mse"]), 76140.0 / 9.0, 1e-9);
  // afex 1.2.1: anova(aov_car(rt ~ Error(id/(angle * noise)), md_12.1)) -> angle MSE 3702.022471910 beside den Df 17.31
  EXPECT_NEAR(number(angle["mse_gg"]), 3702.022471910, 1e-8);
  EXPECT_NE(j["eta_p2_ci90_method"].get<std::string>().find("MBESS"), std::string::npos);
  EXPECT_EQ(j["descriptives"].size(), 6u);
  const CliRun text = dtlab("stats rm-anova --data " + data("md_12.1.csv") + " --dv rt --subject id --within angle,noise");
  EXPECT_NE(text.out.find("MSE (GG)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("df, MSE and p uncorrected"), std::string::npos) << text.out;
}

TEST(StatsCli, FriedmanAndWilcoxonJsonFields) {
  const std::string wide = write_temp("friedman_wide.csv",
                                      "Round Out,Narrow Angle,Wide Angle\n5.40,5.50,5.55\n5.85,5.70,5.75\n5.20,5.60,5.50\n"
                                      "5.55,5.50,5.40\n5.90,5.85,5.70\n5.45,5.55,5.60\n5.40,5.40,5.35\n5.45,5.50,5.35\n"
                                      "5.25,5.15,5.00\n5.85,5.80,5.70\n5.25,5.20,5.10\n5.65,5.55,5.45\n5.60,5.35,5.45\n"
                                      "5.05,5.00,4.95\n5.50,5.50,5.40\n5.45,5.55,5.50\n5.55,5.55,5.35\n5.45,5.50,5.55\n"
                                      "5.50,5.45,5.25\n5.65,5.60,5.40\n5.70,5.65,5.55\n6.30,6.30,6.25\n");
  const CliRun f = dtlab("stats friedman --data " + wide + " --wide --json");
  ASSERT_EQ(f.rc, 0) << f.err;
  const json fj = json::parse(f.out);
  for (const char* key : {"Q", "df", "p", "p_exact", "kendall_W", "iman_davenport_F", "p_iman_davenport"})
    EXPECT_TRUE(fj.contains(key)) << key;
  // R: friedman.test(RoundingTimes): Friedman chi-squared = 11.143, df = 2, p-value = 0.003805
  EXPECT_TRUE(test::printed(number(fj["Q"]), "11.143"));
  EXPECT_TRUE(test::printed(number(fj["p"]), "0.003805"));
  EXPECT_TRUE(test::printed(number(fj["p_exact"]), "0.00314983"));

  const CliRun mc1 = dtlab("stats friedman --data " + wide + " --wide --exact monte-carlo=2000 --seed 3 --json");
  const CliRun mc2 = dtlab("stats friedman --data " + wide + " --wide --exact monte-carlo=2000 --seed 3 --json");
  ASSERT_EQ(mc1.rc, 0) << mc1.err;
  EXPECT_EQ(json::parse(mc1.out)["p_exact"], json::parse(mc2.out)["p_exact"]);
  EXPECT_EQ(json::parse(mc1.out)["exact_method"], "monte-carlo");

  const std::string pairs = write_temp("wilcoxon_long.csv",
                                       "id,visit,hamilton\n1,first,1.83\n1,second,0.878\n2,first,0.50\n2,second,0.647\n"
                                       "3,first,1.62\n3,second,0.598\n4,first,2.48\n4,second,2.05\n5,first,1.68\n5,second,1.06\n"
                                       "6,first,1.88\n6,second,1.29\n7,first,1.55\n7,second,1.06\n8,first,3.06\n8,second,3.14\n"
                                       "9,first,1.30\n9,second,1.29\n");
  const CliRun w = dtlab("stats wilcoxon --data " + pairs + " --dv hamilton --subject id --within visit --json");
  ASSERT_EQ(w.rc, 0) << w.err;
  const json wj = json::parse(w.out);
  for (const char* key : {"V", "p", "p_exact", "z"}) EXPECT_TRUE(wj.contains(key)) << key;
  // R: wilcox.test(Pair(first, second) ~ 1, data = depression) -> V = 40, p-value = 0.03906
  EXPECT_EQ(number(wj["V"]), 40);
  EXPECT_TRUE(test::printed(number(wj["p"]), "0.03906"));
}

TEST(StatsCli, MissingCellWarnsNamingTheSubject) {
  const std::string csv = write_temp("missing.csv", "id,cond,y\nann,a,1\nann,b,3\nbob,a,2\nbob,b,\ncid,a,2\ncid,b,5\ndan,a,1\ndan,b,4\n");
  const CliRun r = dtlab("stats rm-anova --data " + csv + " --dv y --subject id --within cond --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("warning: listwise deletion"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bob (cond=b)"), std::string::npos) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["n_subjects"], 3);
  EXPECT_EQ(j["dropped_subjects"], json::array({"bob"}));
}

TEST(StatsCli, InfiniteAndUndefinedValuesInJson) {
  const std::string csv = write_temp("zero_var.csv", "g,y\na,1.5\na,1.5\nb,2.5\nb,2.5\n");
  const CliRun r = dtlab("stats anova --data " + csv + " --dv y --between g --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json e = json::parse(r.out)["effects"][0];
  EXPECT_EQ(e["F"], "Infinity");
  EXPECT_EQ(number(e["p"]), 0.0);
  EXPECT_EQ(e["log10_p"], "-Infinity");
  EXPECT_TRUE(e["mauchly_W"].is_null());
}

struct BadInput {
  const char* what;
  std::string args;
  int code;
  const char* needle;
};

TEST(StatsCli, BadInputExitsWithCodeAndPlace) {
  const std::string text = write_temp("text.csv", "id,cond,rt\n1,a,400\n1,b,fast\n");
  const std::string nan = write_temp("nan.csv", "id,cond,rt\n1,a,NaN\n1,b,3\n");
  const std::string ragged = write_temp("ragged.csv", "id,cond,rt\n1,a,400\n1,b\n");
  const std::vector<BadInput> cases{
      {"text in dv", "stats rm-anova --data " + text + " --dv rt --subject id --within cond", 1, "text.csv:3:3: rt: expected a number"},
      {"NaN in dv", "stats rm-anova --data " + nan + " --dv rt --subject id --within cond", 1, "nan.csv:2:3: rt: NaN and Inf are not accepted"},
      {"ragged row", "stats rm-anova --data " + ragged + " --dv rt --subject id --within cond", 1, "ragged.csv:3: expected 3 fields"},
      {"unknown column", "stats rm-anova --data " + text + " --dv time --subject id --within cond", 1, "time: no such column"},
      {"missing file", "stats anova --data /nonexistent/x.csv --dv y --between g", 3, "cannot open"},
      {"bad --exact", "stats friedman --data " + text + " --dv rt --subject id --within cond --exact sometimes", 2, "--exact must be"},
      {"rm-anova without --within", "stats rm-anova --data " + text + " --dv rt --subject id", 2, "needs --subject COL and --within"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const CliRun r = dtlab(c.args);
    EXPECT_EQ(r.rc, c.code) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

// Broke: text output of friedman segfaulted (exit 139) with no complete block
// or a one-level factor (mean_ranks read out of bounds).
TEST(StatsCli, FriedmanWithoutBlocksOrWithOneLevelExitsOneNotCrashes) {
  const std::string none = write_temp("fr_none.csv", "id,cond,y\na,x,1\na,y,\nb,x,2\nb,y,NA\n");
  const std::string one = write_temp("fr_one.csv", "id,cond,y\na,x,1\nb,x,2\nc,x,5\n");
  for (const auto& [file, needle] : {std::pair{none, "no subject has every cell"}, std::pair{one, "at least two treatments"}}) {
    for (const char* json : {"", " --json"}) {
      const CliRun r = dtlab("stats friedman --data " + file + " --dv y --subject id --within cond" + json);
      EXPECT_EQ(r.rc, 1) << r.err;
      EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    }
  }
}

// Broke: two levels with W = 1 printed "Iman-Davenport F(1, 7) = Inf, p = 1e-Inf".
TEST(StatsCli, PerfectAgreementPrintsReadably) {
  std::string csv = "id,cond,y\n";
  for (int i = 1; i <= 8; ++i) csv += std::to_string(i) + ",a," + std::to_string(i) + "\n" + std::to_string(i) + ",b," + std::to_string(i + 10) + "\n";
  const std::string file = write_temp("fr_w1.csv", csv);
  const CliRun r = dtlab("stats friedman --data " + file + " --dv y --subject id --within cond");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("Iman-Davenport F(1, 7) = Infinity, p = 0\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("e-Inf"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("perfect agreement"), std::string::npos) << r.err;
  const CliRun j = dtlab("stats friedman --data " + file + " --dv y --subject id --within cond --json");
  EXPECT_EQ(json::parse(j.out)["iman_davenport_F"], "Infinity");
  EXPECT_EQ(number(json::parse(j.out)["p_iman_davenport"]), 0.0);
}

// Broke: values near 1.7e308 printed NA for SS, F and mean without a word.
TEST(StatsCli, OverflowExitsOneNamingIt) {
  const std::string between = write_temp("big_between.csv", "g,y\na,1.7e308\na,-1.7e308\nb,1\nb,2\n");
  const std::string within = write_temp("big_within.csv", "id,cond,y\na,x,1.7e308\na,y,-1.7e308\nb,x,1\nb,y,2\nc,x,4\nc,y,3\n");
  const CliRun a = dtlab("stats anova --data " + between + " --dv y --between g");
  EXPECT_EQ(a.rc, 1);
  EXPECT_NE(a.err.find("overflow"), std::string::npos) << a.err;
  const CliRun rm = dtlab("stats rm-anova --data " + within + " --dv y --subject id --within cond");
  EXPECT_EQ(rm.rc, 1);
  EXPECT_NE(rm.err.find("overflow"), std::string::npos) << rm.err;
  // Wilcoxon ranks the differences (as R); the paired t beside it warns.
  const CliRun w = dtlab("stats wilcoxon --data " + within + " --dv y --subject id --within cond --json");
  ASSERT_EQ(w.rc, 0) << w.err;
  EXPECT_NE(w.err.find("overflow"), std::string::npos) << w.err;
  EXPECT_EQ(number(json::parse(w.out)["V"]), 4.5);  // d = Inf, -1, 1: ranks 3, 1.5, 1.5; V = 3 + 1.5
}

// Broke: a NUL byte made a second subject; a 10 MB field was echoed whole.
TEST(StatsCli, NulBytesAndHugeFieldsGiveShortErrors) {
  const std::string nul = write_temp("nul.csv", std::string("id,cond,y\na,x,1\na\0b,y,2\n", 24));
  const CliRun r = dtlab("stats rm-anova --data " + nul + " --dv y --subject id --within cond");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("nul.csv:3:1: NUL byte"), std::string::npos) << r.err;
  const std::string huge = write_temp("huge.csv", "id,cond,y\na,x,1\na,y," + std::string(10 << 20, '7') + "x\n");
  const CliRun h = dtlab("stats rm-anova --data " + huge + " --dv y --subject id --within cond");
  EXPECT_EQ(h.rc, 1);
  EXPECT_LT(h.err.size(), 500u);
  EXPECT_NE(h.err.find("(10485761 bytes)"), std::string::npos) << h.err.substr(0, 500);
}

// Broke: "1 trials", "n = 1 participants": counts agree with their noun.
TEST(StatsCli, CountsAgreeWithTheirNoun) {
  const std::string one = write_temp("one_subject.csv", "id,cond,y\na,x,1\na,y,3\n");
  const CliRun r = dtlab("stats rm-anova --data " + one + " --dv y --subject id --within cond");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("(1 subject;"), std::string::npos) << r.out;
  const CliRun w = dtlab("stats wilcoxon --data " + one + " --dv y --subject id --within cond");
  EXPECT_NE(w.out.find("(1 pair,"), std::string::npos) << w.out;
}

// Paired t: one-sided CI as R, constant differences warned.
// R 4.2.2: t.test(c(5,6,7,8,9), c(4,5,6,7,8), paired = TRUE) -> Error: data are essentially constant
TEST(StatsCli, PairedTWarnsAndFollowsROneSided) {
  const std::string pairs = write_temp("const_pairs.csv", "id,c,y\n1,a,5\n1,b,4\n2,a,6\n2,b,5\n3,a,7\n3,b,6\n4,a,8\n4,b,7\n5,a,9\n5,b,8\n");
  const CliRun r = dtlab("stats wilcoxon --data " + pairs + " --dv y --subject id --within c");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("essentially constant"), std::string::npos) << r.err;
  const CliRun less = dtlab("stats wilcoxon --data " + data("md_12.1.csv") +
                            " --dv rt --subject id --within noise --aggregate mean --alternative less --json");
  ASSERT_EQ(less.rc, 0) << less.err;
  EXPECT_EQ(json::parse(less.out)["paired_t"]["ci_low"], "-Infinity");
}

// Issue 13 item 7: --where, practice rows, excluded rows, repeated rows.
TEST(StatsCli, RowSelectionIsStatedAndUndoable) {
  const std::string header = "participant,session,transparency,task,trial,practice,excluded,completion_time_s,trial_seed,protocol_sha256\n";
  std::string csv = header;
  const char* ids[] = {"p1", "p2", "p3", "p4"};
  for (int p = 0; p < 4; ++p)
    for (const char* level : {"off", "on"}) {
      const int base = 10 + p * 3 + (std::string(level) == "on" ? 5 + p : 0);
      csv += std::string(ids[p]) + ",1," + level + ",T1,1,1,," + std::to_string(base + 100) + ",1,abc\n";  // practice
      csv += std::string(ids[p]) + ",1," + level + ",T1,1,0," + (p == 3 ? "fell asleep" : "") + "," + std::to_string(base) + ",2,abc\n";
      csv += std::string(ids[p]) + ",1," + level + ",T2,1,0,," + std::to_string(base * 2) + ",3,abc\n";
    }
  const std::string file = write_temp("export.csv", csv);
  const std::string base = "stats rm-anova --data " + file + " --dv completion_time_s --subject participant --within transparency";
  // Practice and T2 rows would repeat cells: without --where the repeats are an error naming lines.
  const CliRun repeats = dtlab(base);
  EXPECT_EQ(repeats.rc, 1);
  EXPECT_NE(repeats.err.find("second row for the cell"), std::string::npos) << repeats.err;
  const CliRun r = dtlab(base + " --where task=T1 --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["rows"]["read"], 24);
  EXPECT_EQ(j["rows"]["practice_left_out"], 8);
  EXPECT_EQ(j["rows"]["excluded_left_out"], 2);
  EXPECT_EQ(j["rows"]["where_left_out"], 8);
  EXPECT_EQ(j["n_subjects"], 3);
  // on - off per kept participant: 5, 6, 7 -> F(1, 2) = mean^2 n / var = 36 * 3 / 1 = 108
  EXPECT_NEAR(number(j["effects"][0]["F"]), 108.0, 1e-9);
  const CliRun text = dtlab(base + " --where task=T1");
  EXPECT_NE(text.out.find("8 rows of practice trials left out (the default for a dtlab export; --include-practice keeps them)"),
            std::string::npos) << text.out;
  EXPECT_NE(text.out.find("2 rows of excluded participants or trials left out"), std::string::npos) << text.out;
  const CliRun kept = dtlab(base + " --where task=T1 --with-excluded --json");
  EXPECT_EQ(json::parse(kept.out)["n_subjects"], 4);
  const CliRun practice = dtlab(base + " --where task=T1 --include-practice --aggregate mean --json");
  ASSERT_EQ(practice.rc, 0) << practice.err;
  EXPECT_EQ(json::parse(practice.out)["rows"]["practice_left_out"], 0);
  const CliRun neq = dtlab(base + " --where task!=T2 --json");
  EXPECT_EQ(json::parse(neq.out)["rows"]["where_left_out"], 8);
  const CliRun median = dtlab(base + " --aggregate median --json");
  ASSERT_EQ(median.rc, 0) << median.err;
  const CliRun bad = dtlab(base + " --where nosuch=1");
  EXPECT_EQ(bad.rc, 1);
  EXPECT_NE(bad.err.find("nosuch: no such column for --where; the header has: participant, session, transparency"),
            std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find(file + ":1"), std::string::npos) << "names the file and the header line: " << bad.err;
  const CliRun no_practice = dtlab("stats rm-anova --data " + data("md_12.1.csv") +
                                   " --dv rt --subject id --within angle,noise --exclude-practice");
  EXPECT_EQ(no_practice.rc, 1);
  EXPECT_NE(no_practice.err.find("--exclude-practice needs a column named practice; the header has: "),
            std::string::npos) << no_practice.err;
  EXPECT_NE(repeats.err.find("--aggregate mean|median"), std::string::npos) << repeats.err;
  EXPECT_EQ(dtlab(base + " --where =x").rc, 2);
  EXPECT_EQ(dtlab(base + " --exclude-practice --include-practice").rc, 2);
  EXPECT_EQ(dtlab(base + " --aggregate mode").rc, 2);
}

// The follow-ups of issue 13 through the command line (values: test_followup_power.cpp,
// test_assumptions_apa.cpp, each against R).
TEST(StatsCli, RmAnovaFollowUpsAndWilcoxonOfOneFactor) {
  const CliRun r = dtlab("stats rm-anova --data " + data("md_12.1.csv") +
                         " --dv rt --subject id --within noise,angle --simple-effects --within-ci --normality --json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["simple_effects"].size(), 5u);
  // R: t.test(absent, present, paired = TRUE) at angle 4 -> t = -4.44261658319319
  EXPECT_NEAR(number(j["simple_effects"][1]["contrast"]["statistic"]), -4.44261658319319, 1e-10);
  // R (Cousineau-Morey formula): se of absent:0 = 17.0528589978338
  EXPECT_NEAR(number(j["within_subject_ci"][0]["se"]), 17.0528589978338, 1e-9);
  // R: shapiro.test(residuals) -> W = 0.971873411127596
  EXPECT_NEAR(number(j["normality"]["W"]), 0.971873411127596, 1e-9);
  const CliRun w = dtlab("stats wilcoxon --data " + data("md_12.1.csv") +
                         " --dv rt --subject id --within noise,angle --factor noise --json");
  ASSERT_EQ(w.rc, 0) << w.err;
  // R: t.test(rowMeans(absent cells), rowMeans(present cells), paired = TRUE) -> mean difference -138
  EXPECT_NEAR(number(json::parse(w.out)["paired_t"]["mean_difference"]), -138, 1e-10);
  EXPECT_EQ(dtlab("stats wilcoxon --data " + data("md_12.1.csv") + " --dv rt --subject id --within noise,angle").rc, 2);
}

// Issue 23's statistics through the command line, each value against R
// (tests/analysis/data/stats_r_followups.R; the library tests give the details).
TEST(StatsCli, MixedFollowUpsAggregatedTiesAndExactNotes) {
  // R: pairs(emmeans(aov_car(time ~ group + Error(id/task), d), ~ task), adjust = "holm"): search - locate p 0.1109
  const CliRun m = dtlab("stats rm-anova --data " + data("mixed_posthoc.csv") +
                         " --dv time --subject id --within task --between group --posthoc --simple-effects --json");
  ASSERT_EQ(m.rc, 0) << m.err;
  const json mj = json::parse(m.out);
  const json& sl = mj["posthoc"]["task"][1];
  EXPECT_EQ(sl["test"], "emmeans t");
  EXPECT_EQ(number(sl["df"]), 10);
  EXPECT_TRUE(test::printed(number(sl["p_holm"]), "0.1109"));
  // R: joint_tests(fit, by = "group"): task at novice F(2, 10) = 16.623, p = 0.000661135971654593
  bool found = false;
  for (const auto& row : mj["simple_effects"])
    if (row["factor"] == "task" && row["at"]["group"] == "novice") {
      found = true;
      EXPECT_EQ(row["test"], "emmeans F");
      EXPECT_NEAR(number(row["joint_test"]["p"]), 0.000661135971654593, 1e-12);
    }
  EXPECT_TRUE(found) << m.out;
  const CliRun mt = dtlab("stats rm-anova --data " + data("mixed_posthoc.csv") +
                          " --dv time --subject id --within task --between group --simple-effects");
  EXPECT_NE(mt.out.find("task at group=novice: F(2, 10) = 16.6228"), std::string::npos) << mt.out;
  // A between factor's contrast has Cohen's d (SD pooled over the groups), labelled d, not d_z.
  // R (stats_r_followups.R, section 3): diff(tapply(time, group, mean)) / pooled SD at task = count: 2.37416216015944
  EXPECT_NE(mt.out.find("p_holm = 0.00922188, d = 2.37416\n"), std::string::npos) << mt.out;

  // R: friedman.test on aggregate(time ~ participant + condition, aggregate_ties.csv, mean): 1.333333333333
  const CliRun f = dtlab("stats friedman --data " + data("aggregate_ties.csv") +
                         " --dv time --subject participant --within condition --aggregate mean --json");
  ASSERT_EQ(f.rc, 0) << f.err;
  EXPECT_NEAR(number(json::parse(f.out)["Q"]), 1.333333333333, 1e-11);
  // R: wilcox.test(A, B, paired = TRUE) on the means: V = 0, p-value = 0.371093369523 (four zeros dropped)
  const CliRun w = dtlab("stats wilcoxon --data " + data("aggregate_ties.csv") +
                         " --dv time --subject participant --within condition --where condition!=C --aggregate mean --json");
  ASSERT_EQ(w.rc, 0) << w.err;
  EXPECT_NEAR(number(json::parse(w.out)["p"]), 0.371093369523, 1e-11);

  // k = 8, n = 12: refused at once with the reason in exact_note (was empty after 25 s).
  std::string csv = "id,cond,y\n";
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 8; ++j) csv += "s" + std::to_string(i) + ",c" + std::to_string(j) + "," + std::to_string((i * 5 + j * 3) % 8 + 10 * j) + "\n";
  const CliRun k8 = dtlab("stats friedman --data " + write_temp("k8.csv", csv) + " --dv y --subject id --within cond --exact always --json");
  ASSERT_EQ(k8.rc, 0) << k8.err;
  const json kj = json::parse(k8.out);
  EXPECT_TRUE(kj["p_exact"].is_null());
  EXPECT_NE(kj["exact_note"].get<std::string>().find("state updates for n = 12, k = 8"), std::string::npos) << k8.out;

  // Values near the smallest double: F as for the same data x 1e310 (R: 44.5708154506434), with a warning.
  const CliRun tiny = dtlab("stats rm-anova --data " + data("tiny_values.csv") + " --dv y --subject id --within cond --json");
  ASSERT_EQ(tiny.rc, 0) << tiny.err;
  EXPECT_NEAR(number(json::parse(tiny.out)["effects"][0]["F"]), 44.5708154506434, 1e-10);
  EXPECT_NE(tiny.err.find("below the smallest normal double"), std::string::npos) << tiny.err;
}

}  // namespace
}  // namespace dtlab::stats
