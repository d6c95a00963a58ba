// Repeated-measures and mixed ANOVA against published and R values, each
// with the call that produced it, and the documented hard cases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/stats/rm_anova.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

const Effect& find(const RmAnovaResult& r, const std::string& name) {
  for (const auto& e : r.effects)
    if (e.name == name) return e;
  ADD_FAILURE() << "no effect " << name;
  static Effect none;
  return none;
}

RmAnovaResult run(const LongData& d, const RmAnovaOptions& o = {}) {
  auto r = rm_anova(d, o);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  return r.ok() ? *r : RmAnovaResult{};
}

// Maxwell & Delaney (2004) Table 12.1 (afex::md_12.1): published F and SS.
// R (car 3.x conventions): afex::aov_car(rt ~ 1 + Error(id/(angle*noise)), md_12.1)
//   with summary(): GG, HF, Mauchly; anova(es = "ges").
TEST(RmAnova, MaxwellDelaneyTable12_1) {
  const RmAnovaResult r = run(test::load_long("md_12.1.csv", {"rt", "id", {"angle", "noise"}, {}}));
  ASSERT_EQ(r.effects.size(), 3u);
  EXPECT_EQ(r.n_subjects, 10u);
  const Effect& angle = find(r, "angle");
  const Effect& noise = find(r, "noise");
  const Effect& inter = find(r, "angle:noise");
  // published: SS 289920 / 285660 / 105120, error SS 64080 / 76140 / 20880 (exact)
  EXPECT_TRUE(near_rel(angle.ss, 289920, 1e-13));
  EXPECT_TRUE(near_rel(noise.ss, 285660, 1e-13));
  EXPECT_TRUE(near_rel(inter.ss, 105120, 1e-13));
  EXPECT_TRUE(near_rel(angle.ss_error, 64080, 1e-13));
  EXPECT_TRUE(near_rel(noise.ss_error, 76140, 1e-13));
  EXPECT_TRUE(near_rel(inter.ss_error, 20880, 1e-13));
  // published: angle F(2,18)=40.72, noise F(1,9)=33.77, angle:noise F(2,18)=45.31
  EXPECT_TRUE(printed(angle.F, "40.72"));
  EXPECT_TRUE(printed(noise.F, "33.77"));
  EXPECT_TRUE(printed(inter.F, "45.31"));
  EXPECT_EQ(angle.df1, 2);
  EXPECT_EQ(angle.df2, 18);
  EXPECT_EQ(noise.df2, 9);
  // car conventions (reference folder, REFERENCE_RESULTS.txt B)
  EXPECT_TRUE(printed(angle.gg_epsilon, "0.961637"));
  EXPECT_TRUE(printed(angle.hf_epsilon, "1.217564"));
  EXPECT_TRUE(printed(angle.mauchly_W, "0.960106"));
  EXPECT_TRUE(printed(angle.mauchly_p, "0.84972"));
  EXPECT_TRUE(printed(inter.gg_epsilon, "0.903977"));
  EXPECT_TRUE(printed(inter.hf_epsilon, "1.117870"));
  EXPECT_TRUE(printed(inter.mauchly_W, "0.893777"));
  EXPECT_TRUE(printed(inter.mauchly_p, "0.63814"));
  EXPECT_TRUE(printed(angle.eta_g2, "0.390118"));
  EXPECT_TRUE(printed(noise.eta_g2, "0.386602"));
  EXPECT_TRUE(printed(inter.eta_g2, "0.188266"));
  // HF > 1: p_hf uses min(1, HF), i.e. the uncorrected p; 1-df effect: GG = HF = 1, no Mauchly.
  EXPECT_DOUBLE_EQ(angle.p_hf, angle.p);
  EXPECT_EQ(noise.gg_epsilon, 1.0);
  EXPECT_TRUE(std::isnan(noise.mauchly_W));
  EXPECT_DOUBLE_EQ(noise.p_gg, noise.p);
  EXPECT_GT(angle.p_gg, angle.p);
}

struct EzCase {
  const char* effect;
  double df1, df2;
  const char* F;
  const char* p;
};

// R ez::ezANOVA values from statsmodels' tests (statsmodels/stats/tests/test_anova_rm.py):
//   ezANOVA(data, dv = DV, wid = id, within = .(A, B, D)) on rows 1-16 / 1-48 / all 96.
TEST(RmAnova, StatsmodelsEzAnova) {
  struct Subset {
    size_t rows;
    std::vector<std::string> within;
    std::vector<EzCase> cases;
  };
  const std::vector<Subset> subsets{
      {16, {"B"}, {{"B", 1, 7, "22.4", "0.002125452"}}},
      {48, {"A", "B"}, {{"A", 1, 7, "40.14159", "3.905263e-04"}, {"B", 2, 14, "29.21739", "1.007549e-05"},
                        {"A:B", 2, 14, "17.10545", "1.741322e-04"}}},
      {96, {"A", "B", "D"}, {{"A", 1, 7, "8.7650709", ".021087505"}, {"B", 2, 14, "8.4985785", ".003833921"},
                             {"D", 1, 7, "20.5076546", ".002704428"}, {"A:B", 2, 14, "0.8457797", ".450021759"},
                             {"A:D", 1, 7, "21.7593382", ".002301792"}, {"B:D", 2, 14, "6.2416695", ".011536846"},
                             {"A:B:D", 2, 14, "5.4253359", ".018010647"}}},
  };
  auto table = read_csv_file(test::data_path("statsmodels_anova_rm.csv"));
  ASSERT_TRUE(table.ok());
  for (const auto& s : subsets) {
    SCOPED_TRACE(s.rows);
    CsvTable t = *table;
    t.rows.resize(s.rows);
    t.line.resize(s.rows);
    auto d = long_data_from_csv(t, {"DV", "id", s.within, {}});
    ASSERT_TRUE(d.ok());
    const RmAnovaResult r = run(*d);
    ASSERT_EQ(r.effects.size(), s.cases.size());
    for (const auto& c : s.cases) {
      SCOPED_TRACE(c.effect);
      const Effect& e = find(r, c.effect);
      EXPECT_EQ(e.df1, c.df1);
      EXPECT_EQ(e.df2, c.df2);
      EXPECT_TRUE(printed(e.F, c.F));
      EXPECT_TRUE(printed(e.p, c.p));
    }
  }
}

// pingouin tests (values compared there with JAMOVI / ezANOVA):
//   pg.rm_anova(data=df, dv='Performance', within=['Time', 'Metric'], subject='Subject', detailed=True)
TEST(RmAnova, PingouinTwoWay) {
  const RmAnovaResult r = run(test::load_long("pingouin_rm_anova2.csv", {"Performance", "Subject", {"Time", "Metric"}, {}}));
  const char* F[] = {"33.85228", "26.95919", "12.63227"};
  const char* ng2[] = {"0.25401", "0.35933", "0.08442"};
  const char* np2[] = {"0.78998", "0.74972", "0.58395"};
  const char* gg[] = {"1.0", "0.96910", "0.72717"};
  const char* names[] = {"Time", "Metric", "Time:Metric"};
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    const Effect& e = find(r, names[i]);
    EXPECT_TRUE(printed(e.F, F[i]));
    EXPECT_TRUE(printed(e.eta_g2, ng2[i]));
    EXPECT_TRUE(printed(e.eta_p2, np2[i]));
    EXPECT_TRUE(printed(e.gg_epsilon, gg[i]));
  }
  const Effect& inter = find(r, "Time:Metric");
  EXPECT_TRUE(printed(inter.hf_epsilon, "0.831161"));
  EXPECT_TRUE(printed(inter.mauchly_W, "0.625"));
  EXPECT_TRUE(printed(inter.mauchly_p, "0.1523917"));
  EXPECT_TRUE(printed(find(r, "Metric").mauchly_W, "0.968"));
}

// pingouin: pg.rm_anova(df_wide) on rm_anova_wide.csv (listwise deletion, 9 of 12 subjects):
//   F=5.20065 p=0.00656 ng2=0.34639 np2=0.39397 eps=0.69433 W=0.30678 p_GG=0.01670;
//   car conventions (reference folder): HF=0.943432, Mauchly p=0.163365, p_HF=0.0077827.
TEST(RmAnova, PingouinWideWithListwiseDeletion) {
  auto t = read_csv_file(test::data_path("pingouin_rm_anova_wide.csv"));
  ASSERT_TRUE(t.ok());
  auto d = long_data_from_wide_csv(*t, WideRoles{});
  ASSERT_TRUE(d.ok());
  const RmAnovaResult r = run(*d);
  EXPECT_EQ(r.n_subjects, 9u);
  ASSERT_EQ(r.dropped_subjects.size(), 3u);
  ASSERT_FALSE(r.warnings.empty());
  for (const char* who : {"line 4", "line 8", "line 12"}) EXPECT_NE(r.warnings[0].find(who), std::string::npos) << r.warnings[0];
  const Effect& e = find(r, "condition");
  EXPECT_TRUE(printed(e.F, "5.20065"));
  EXPECT_TRUE(printed(e.p, "0.00656"));
  EXPECT_TRUE(printed(e.eta_g2, "0.34639"));
  EXPECT_TRUE(printed(e.eta_p2, "0.39397"));
  EXPECT_TRUE(printed(e.gg_epsilon, "0.69433"));
  EXPECT_TRUE(printed(e.mauchly_W, "0.30678"));
  EXPECT_TRUE(printed(e.p_gg, "0.01670"));
  EXPECT_TRUE(printed(e.hf_epsilon, "0.943432"));
  EXPECT_TRUE(printed(e.mauchly_p, "0.163365"));
  EXPECT_TRUE(printed(e.p_hf, "0.0077827"));
}

// pingouin mixed_anova.csv with Time as the only (within) factor, 60 subjects:
//   pg.rm_anova(dv='Scores', within='Time', subject='Subject'): F=3.91280 p=0.02263 ng2=0.03998 np2=0.06219
//   pg.sphericity(...): W=0.999 p=0.964
TEST(RmAnova, PingouinOneWaySixtySubjects) {
  const RmAnovaResult r = run(test::load_long("pingouin_mixed_anova.csv", {"Scores", "Subject", {"Time"}, {}}));
  EXPECT_EQ(r.n_subjects, 60u);
  const Effect& e = find(r, "Time");
  EXPECT_TRUE(printed(e.F, "3.91280"));
  EXPECT_TRUE(printed(e.p, "0.02263"));
  EXPECT_TRUE(printed(e.eta_g2, "0.03998"));
  EXPECT_TRUE(printed(e.eta_p2, "0.06219"));
  EXPECT_TRUE(printed(e.mauchly_W, "0.999"));
  EXPECT_TRUE(printed(e.mauchly_p, "0.964"));
}

// Mixed design, unbalanced between cells: O'Brien & Kaiser (1985) data (carData::OBrienKaiser,
// afex::obk.long). afex 1.x tests: aov_car(value ~ treatment * gender + Error(id/(phase*hour)),
//   data = obk.long, observed = "gender", correction = "none")
//   phase F(2,20)=16.1329196993199 p=6.73163655770545e-05; hour F(4,40)=16.6856704980843
//   p=4.02664339633774e-08; phase:hour F(8,80)=1.17990398215104 p=0.32158661418337.
// Published (O'Brien & Kaiser 1985, Table 8): treatment F(2,10)=3.94, gender F(1,10)=3.66,
//   treatment:gender F(2,10)=2.86.
TEST(RmAnova, MixedDesignMatchesAfexObkLong) {
  RmAnovaOptions o;
  o.observed = {"gender"};
  const RmAnovaResult r = run(test::load_long("obk_long.csv", {"value", "id", {"phase", "hour"}, {"treatment", "gender"}}), o);
  ASSERT_EQ(r.effects.size(), 15u);
  EXPECT_EQ(r.effects[0].name, "treatment");
  EXPECT_EQ(r.effects[3].name, "phase");
  EXPECT_EQ(r.effects[4].name, "treatment:phase");
  struct Row {
    const char* name;
    double df1, df2;
    double F, p;
  } rows[] = {{"phase", 2, 20, 16.1329196993199, 6.73163655770545e-05},
              {"hour", 4, 40, 16.6856704980843, 4.02664339633774e-08},
              {"phase:hour", 8, 80, 1.17990398215104, 0.32158661418337}};
  for (const auto& row : rows) {
    SCOPED_TRACE(row.name);
    const Effect& e = find(r, row.name);
    EXPECT_EQ(e.df1, row.df1);
    EXPECT_EQ(e.df2, row.df2);
    EXPECT_TRUE(near_rel(e.F, row.F, 1e-11));
    EXPECT_TRUE(near_rel(e.p, row.p, 1e-9));
  }
  EXPECT_TRUE(printed(find(r, "treatment").F, "3.94"));
  EXPECT_TRUE(printed(find(r, "gender").F, "3.66"));
  EXPECT_TRUE(printed(find(r, "treatment:gender").F, "2.86"));
  EXPECT_TRUE(std::isnan(find(r, "treatment").gg_epsilon)) << "between effects have no sphericity";
  // observed gender: eta_g2 of effects without gender are smaller than with no observed factor
  const RmAnovaResult plain = run(test::load_long("obk_long.csv", {"value", "id", {"phase", "hour"}, {"treatment", "gender"}}));
  EXPECT_LT(find(r, "phase").eta_g2, find(plain, "phase").eta_g2);
  EXPECT_DOUBLE_EQ(find(r, "phase").F, find(plain, "phase").F);
}

// The API the study report uses: plain vectors in.
TEST(RmAnova, InMemoryLongDataGivesTheSameAsCsv) {
  LongData d;
  d.subject = {"a", "a", "a", "b", "b", "b", "c", "c", "c", "d", "d", "d"};
  d.within.push_back({"cond", {"x", "y", "z", "x", "y", "z", "x", "y", "z", "x", "y", "z"}});
  d.dv = Measurements::from_doubles({1, 3, 4, 2, 2, 5, 3, 5, 6, 2, 4, 4});
  const RmAnovaResult r = run(d);
  // Hand computation (textbook two-way decomposition, Maxwell & Delaney ch. 11): condition means
  // 2, 3.5, 4.75, grand mean 41/12; SS_cond = 4 sum((mean - 41/12)^2) = 91/6; SS_subject = 83/12;
  // SS_total = 165 - 12 (41/12)^2 = 299/12; SS_error = SS_total - SS_cond - SS_subject = 17/6.
  const Effect& e = find(r, "cond");
  EXPECT_NEAR(e.ss, 91.0 / 6.0, 1e-12);
  EXPECT_NEAR(e.ss_error, 17.0 / 6.0, 1e-12);
  EXPECT_NEAR(e.F, (91.0 / 12.0) / (17.0 / 36.0), 1e-11);
  // generalized eta squared = SS_cond / (SS_cond + SS_subject + SS_error)
  EXPECT_NEAR(e.eta_g2, (91.0 / 6.0) / (91.0 / 6.0 + 83.0 / 12.0 + 17.0 / 6.0), 1e-12);
}

LongData grid(const std::vector<std::vector<double>>& y) {
  LongData d;
  d.within.push_back({"cond", {}});
  std::vector<double> v;
  for (size_t s = 0; s < y.size(); ++s)
    for (size_t c = 0; c < y[s].size(); ++c) {
      d.subject.push_back("s" + std::to_string(s + 1));
      d.within[0].level.push_back("c" + std::to_string(c + 1));
      v.push_back(y[s][c]);
    }
  d.dv = Measurements::from_doubles(v);
  return d;
}

TEST(RmAnovaHardCases, ParallelProfilesGiveInfiniteF) {
  // y = subject + condition effect exactly (integers given as doubles, which are
  // exact): the error SS is exactly 0. Decimal data: test_edge_cases.cpp.
  const RmAnovaResult r = run(grid({{1, 3, 8}, {11, 13, 18}, {26, 28, 33}, {5, 7, 12}}));
  const Effect& e = find(r, "cond");
  EXPECT_EQ(e.ss_error, 0.0);
  EXPECT_EQ(e.F, INFINITY);
  EXPECT_EQ(e.p, 0.0);
  EXPECT_EQ(e.log10_p, -INFINITY);
  EXPECT_TRUE(std::isnan(e.gg_epsilon)) << "GG is 0/0 with a zero error matrix";
  EXPECT_EQ(e.p_gg, 0.0);
  EXPECT_FALSE(r.warnings.empty());
}

TEST(RmAnovaHardCases, ConstantDataIsZeroOverZero) {
  const RmAnovaResult r = run(grid({{2, 2, 2}, {2, 2, 2}, {2, 2, 2}}));
  EXPECT_TRUE(std::isnan(find(r, "cond").F));
  EXPECT_TRUE(std::isnan(find(r, "cond").p));
}

TEST(RmAnovaHardCases, OneSubjectHasNoErrorDf) {
  const RmAnovaResult r = run(grid({{1, 2, 4}}));
  const Effect& e = find(r, "cond");
  EXPECT_EQ(e.df2, 0);
  EXPECT_TRUE(std::isnan(e.F));
  EXPECT_TRUE(std::isnan(e.p));
  bool warned = false;
  for (const auto& w : r.warnings) warned = warned || w.find("one subject") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(RmAnovaHardCases, OneLevelIsNotTested) {
  const RmAnovaResult r = run(grid({{1}, {2}, {4}}));
  EXPECT_TRUE(r.effects.empty());
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("one level"), std::string::npos);
}

TEST(RmAnovaHardCases, TwoSubjectsThreeLevels) {
  // Reference folder H: n = 2, k = 3 -> GG = 1/(k-1) = 0.5, Mauchly W = 0 (rank deficient), HF 0/0.
  const RmAnovaResult r = run(grid({{1, 4, 2}, {3, 5, 9}}));
  const Effect& e = find(r, "cond");
  EXPECT_EQ(e.gg_epsilon, 0.5);
  EXPECT_EQ(e.mauchly_W, 0.0);
  EXPECT_TRUE(std::isnan(e.mauchly_p));
  EXPECT_TRUE(std::isnan(e.hf_epsilon));
  EXPECT_TRUE(std::isnan(e.p_hf));
  EXPECT_TRUE(std::isfinite(e.p_gg));
}

TEST(RmAnovaHardCases, MissingCellRemovesTheSubjectAndNamesIt) {
  LongData holed = test::long_from_text(
      "id,cond,y\ns1,c1,1\ns1,c2,3\ns1,c3,4\ns2,c1,2\ns2,c2,2\ns3,c1,3\ns3,c2,5\ns3,c3,6\ns4,c1,2\ns4,c2,4\ns4,c3,4\ns5,c1,7\ns5,c2,NA\ns5,c3,1\n",
      {"y", "id", {"cond"}, {}});
  const RmAnovaResult r = run(holed);
  EXPECT_EQ(r.n_subjects, 3u);
  ASSERT_EQ(r.dropped_subjects.size(), 2u);
  EXPECT_EQ(r.dropped_subjects[0], "s2");
  EXPECT_EQ(r.dropped_subjects[1], "s5");
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("s2 (cond=c3)"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("s5 (cond=c2)"), std::string::npos) << r.warnings[0];
  // Same as analysing the complete subjects only.
  const RmAnovaResult complete = run(grid({{1, 3, 4}, {3, 5, 6}, {2, 4, 4}}));
  EXPECT_DOUBLE_EQ(find(r, "cond").F, find(complete, "cond").F);
}

TEST(RmAnovaHardCases, RepeatedRowsAreAveragedWhenAskedWithAWarning) {
  LongData twice = test::long_from_text(
      "id,cond,y\na,x,1\na,x,3\na,y,5\nb,x,2\nb,y,4\nb,y,8\nc,x,0\nc,y,3\n", {"y", "id", {"cond"}, {}});
  twice.aggregate = Aggregate::mean;
  const RmAnovaResult r = run(twice);
  const RmAnovaResult means = run(grid({{2, 5}, {2, 6}, {0, 3}}));
  EXPECT_DOUBLE_EQ(find(r, "cond").F, find(means, "cond").F);
  bool warned = false;
  for (const auto& w : r.warnings) warned = warned || w.find("more than one row") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(RmAnovaHardCases, BetweenFactorChangingWithinASubjectIsAnError) {
  auto t = parse_csv("id,g,cond,y\n1,a,x,1\n1,b,y,2\n2,a,x,3\n2,a,y,4\n", "mixed.csv");
  ASSERT_TRUE(t.ok());
  auto d = long_data_from_csv(*t, {"y", "id", {"cond"}, {"g"}});
  ASSERT_TRUE(d.ok());
  auto r = rm_anova(*d);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 3);
  EXPECT_EQ(r.error().field, "g");
  EXPECT_NE(r.error().message.find("mixed.csv:2"), std::string::npos) << r.error().message;
}

TEST(RmAnovaHardCases, PFarBelowTheDoubleRangeKeepsAFiniteLog) {
  // 300 subjects, three conditions 1000 apart, small noise: F is astronomically large.
  std::vector<std::vector<double>> y;
  for (int s = 0; s < 300; ++s) {
    const double noise = ((s * 7919) % 13) * 1e-3;
    y.push_back({s + noise, s + 1000 - noise, s + 2000 + 2 * noise});
  }
  const RmAnovaResult r = run(grid(y));
  const Effect& e = find(r, "cond");
  EXPECT_GT(e.F, 1e9);
  EXPECT_TRUE(std::isfinite(e.log10_p));
  EXPECT_LT(e.log10_p, -320);
  EXPECT_EQ(e.p, 0.0);
  // F(2, d2) closed form: log10 p = -(d2/2) log10(1 + 2F/d2)
  EXPECT_TRUE(near_rel(e.log10_p, -(e.df2 / 2) * std::log10(1 + 2 * e.F / e.df2), 1e-10));
}

}  // namespace
}  // namespace dtlab::stats
