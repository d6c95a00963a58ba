// The report's own small computations: the repeated-measures correlation
// against R's rmcorr, the participant x cell aggregation and its missing-data
// notes, p-value text for tiny and underflowing p, and SVG inlining (prolog
// gone, ids prefixed, references follow).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/report/detail/cells.h"
#include "analysis/report/detail/document.h"
#include "analysis/report/detail/format.h"
#include "analysis/report/detail/rmcorr.h"

namespace dtlab::report::detail {
namespace {

TEST(RmCorr, BlandAltman1995MatchesRmcorr) {
  // Bland & Altman (1995), BMJ 310:446, Table 1: intramural pH and PaCO2 of 8 subjects (47 pairs), as shipped
  // in R package rmcorr (`bland1995`). R: rmcorr(Subject, PaCO2, pH, bland1995) (rmcorr 0.6/0.7):
  // r = -0.5067697, df = 38, p-value = 0.0008471081, 95% CI -0.7067146 -0.2318631
  const std::vector<int> n = {4, 4, 9, 5, 8, 6, 3, 8};
  const std::vector<double> ph = {6.68, 6.53, 6.43, 6.33, 6.85, 7.06, 7.13, 7.17, 7.40, 7.42, 7.41, 7.37,
                                  7.34, 7.35, 7.28, 7.30, 7.34, 7.36, 7.33, 7.29, 7.30, 7.35, 7.35, 7.30,
                                  7.30, 7.37, 7.27, 7.28, 7.32, 7.32, 7.38, 7.30, 7.29, 7.33, 7.31, 7.33,
                                  6.86, 6.94, 6.92, 7.19, 7.29, 7.21, 7.25, 7.20, 7.19, 6.77, 6.82};
  const std::vector<double> paco2 = {3.97, 4.12, 4.09, 3.97, 5.27, 5.37, 5.41, 5.44, 5.67, 3.64, 4.32, 4.73,
                                     4.96, 5.04, 5.22, 4.82, 5.07, 5.67, 5.10, 5.53, 4.75, 5.51, 4.28, 4.44,
                                     4.32, 3.23, 4.46, 4.72, 4.75, 4.99, 4.78, 4.73, 5.12, 4.93, 5.03, 4.93,
                                     6.85, 6.44, 6.52, 5.28, 4.56, 4.34, 4.32, 4.41, 3.69, 6.09, 5.58};
  std::vector<std::string> subject;
  for (size_t s = 0; s < n.size(); ++s)
    for (int i = 0; i < n[s]; ++i) subject.push_back(std::to_string(s + 1));
  ASSERT_EQ(subject.size(), 47u);
  const RmCorr r = rm_corr(subject, paco2, ph);
  EXPECT_NEAR(r.r, -0.5067697, 1e-7);
  EXPECT_EQ(r.df, 38);
  EXPECT_NEAR(r.p, 0.0008471081, 1e-10);
  EXPECT_NEAR(r.ci_low, -0.7067146, 1e-7);
  EXPECT_NEAR(r.ci_high, -0.2318631, 1e-7);
  // A constant offset of 1e9 (large completion times) changes nothing: values are centred per group first.
  std::vector<double> shifted = paco2;
  for (double& v : shifted) v += 1e9;
  EXPECT_NEAR(rm_corr(subject, shifted, ph).r, -0.5067697, 1e-6);
}

TEST(RmCorr, DegenerateCasesAreUndefinedNotCrashes) {
  // No within-group variation in y: r undefined.
  const RmCorr a = rm_corr({"a", "a", "b", "b"}, {1, 2, 3, 4}, {5, 5, 6, 6});
  EXPECT_TRUE(std::isnan(a.r));
  // One pair per group: df = N - G - 1 < 1.
  const RmCorr b = rm_corr({"a", "b", "c"}, {1, 2, 3}, {3, 1, 2});
  EXPECT_TRUE(std::isnan(b.p));
  // Missing values are dropped.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const RmCorr c = rm_corr({"a", "a", "a", "b", "b", "b"}, {1, 2, nan, 1, 2, 3}, {1, 2, 9, 2, 3, 4});
  EXPECT_EQ(c.n, 5u);
  EXPECT_NEAR(c.r, 1.0, 1e-12);
}

// APA 7th ed., 6.36: p to three decimals without a leading zero, "< .001" below; the exact value
// stays in report.json (an underflowed p of 0 included).
TEST(Format, PValuesInApaStyle) {
  struct Case {
    double p;
    const char* text;
  };
  const Case cases[] = {
      {0.0240, ".024"},     {0.797, ".797"},   {0.0017, ".002"},   {0.0010004, ".001"},
      {3.905263e-04, "< .001"}, {2.1e-12, "< .001"}, {0.0, "< .001"}, {0.9996, "> .999"},
      {1.0, "> .999"},      {std::nan(""), "—"},
  };
  for (const auto& c : cases) EXPECT_EQ(p_text(c.p), c.text) << c.p;
  EXPECT_EQ(bounded(0.4921), ".49");
  EXPECT_EQ(bounded(-0.4951, 3), "-.495");
  EXPECT_EQ(bounded(std::nan("")), "—");
  EXPECT_EQ(fixed(-0.0001, 2), "0.00");
  EXPECT_EQ(mean_sd(56.256, 38.72, 2), "56.26 (38.72)");
  EXPECT_EQ(f_text(0.7164), "0.72");  // APA: F with two decimals, as in the sentences
  EXPECT_EQ(df_text(15), "15");
  EXPECT_EQ(df_text(12.4671), "12.47");
  EXPECT_TRUE(num(std::nan("")).is_null());
  EXPECT_EQ(num(INFINITY), "Infinity");
}

TEST(InlineSvg, StripsPrologAndMakesIdsUnique) {
  const std::string svg =
      "<?xml version=\"1.0\" encoding=\"utf-8\"  standalone=\"no\"?>\n<svg \n viewBox=\"0 0 10 10\"\n"
      " xmlns=\"http://www.w3.org/2000/svg\"\n xmlns:xlink=\"http://www.w3.org/1999/xlink\"\n>\n"
      "<defs><circle id='gpDot' r='1'/><path id=\"gpPt0\" d='M0,0'/></defs>\n"
      "<use xlink:href='#gpDot'/><use href=\"#gpPt0\"/><rect fill=\"url(#gpPt0)\"/>\n"
      "<text>id='gpDot' stays text</text><g id='key'/><g id='key'/></svg>\n";
  const std::string out = inline_svg(svg, "fig-");
  EXPECT_EQ(out.rfind("<svg", 0), 0u);
  EXPECT_EQ(out.find("xmlns"), std::string::npos);
  EXPECT_EQ(out.find("http"), std::string::npos);
  EXPECT_NE(out.find("id='fig-gpDot'"), std::string::npos);
  EXPECT_NE(out.find("id=\"fig-gpPt0\""), std::string::npos);
  EXPECT_NE(out.find("xlink:href='#fig-gpDot'"), std::string::npos);
  EXPECT_NE(out.find("href=\"#fig-gpPt0\""), std::string::npos);
  EXPECT_NE(out.find("url(#fig-gpPt0)"), std::string::npos);
  EXPECT_NE(out.find("<text>id='gpDot' stays text</text>"), std::string::npos);
  // An id gnuplot repeats inside one SVG becomes unique.
  EXPECT_NE(out.find("<g id='fig-key'/><g id='fig-key-2'/>"), std::string::npos);
}

TEST(Latex, EscapesEverySpecialCharacterAndMapsTheReportsSymbols) {
  EXPECT_EQ(latex_escape("50% of a_b & c#d $x {y} ~z ^w \\ <a|b>"),
            "50\\% of a\\_b \\& c\\#d \\$x \\{y\\} \\textasciitilde{}z \\textasciicircum{}w "
            "\\textbackslash{} \\textless{}a\\textbar{}b\\textgreater{}");
  EXPECT_EQ(latex_escape("`trials_2.csv` η²p − 1 × 2 — χ²"),
            "\\texttt{trials\\_2.csv} $\\eta$\\textsuperscript{2}p $-$ 1 $\\times$ 2 --- "
            "$\\chi$\\textsuperscript{2}");
}

TEST(Latex, TablesUseBooktabsAndSpanningGroups) {
  Document doc;
  doc.title = "Results: A & B";
  Section s{"time", "Completion time", 2, {}};
  Table t;
  t.id = "table-time";
  t.caption = "Time (s) of 100% of trials";
  t.groups = {{"this study", 2}, {"article", 1}};
  t.header = {"Task", "off", "off"};
  t.rows = {{"T_1", "1.00", "2.00"}};
  t.notes = {"n = 8"};
  s.add(t);
  doc.sections.push_back(s);
  const std::string tex = render_latex(doc);
  EXPECT_NE(tex.find("\\usepackage{booktabs}"), std::string::npos);
  EXPECT_NE(tex.find("\\title{Results: A \\& B}"), std::string::npos);
  EXPECT_NE(tex.find("\\caption{Time (s) of 100\\% of trials}\\label{table-time}"), std::string::npos);
  EXPECT_NE(tex.find("\\begin{tabular}{@{}lrr@{}}\n\\toprule\n"), std::string::npos);
  EXPECT_NE(tex.find("\\multicolumn{2}{c}{this study} & \\multicolumn{1}{c}{article} \\\\\n"
                     "\\cmidrule(lr){1-2}\\cmidrule(lr){3-3}"),
            std::string::npos);
  EXPECT_NE(tex.find("T\\_1 & 1.00 & 2.00 \\\\\n\\bottomrule"), std::string::npos);
  EXPECT_NE(tex.find("\\tablenotes{n = 8}"), std::string::npos);
  EXPECT_EQ(tex.rfind("\\end{document}\n"), tex.size() - 15);
}

TEST(Reducers, AggregatedRelativeErrorIsTheArticles) {
  // |sum truths - sum answers| / sum truths over answered trials: truths 25 30 35, answers 26 30 34 -> 0;
  // a trial without an answer is left out of both sums.
  std::vector<TrialRow> rows(4);
  const int truth[] = {25, 30, 35, 40};
  const int answer[] = {26, 30, 34, 0};
  for (int i = 0; i < 4; ++i) {
    rows[static_cast<size_t>(i)].truth = store::Count{truth[i]};
    if (i < 3) rows[static_cast<size_t>(i)].answer = store::Count{answer[i]};
  }
  std::vector<const TrialRow*> ptr;
  for (const auto& r : rows) ptr.push_back(&r);
  EXPECT_EQ(aggregated_relative_error()(ptr), 0.0);
  rows[2].answer = store::Count{40};  // 96 for 90
  EXPECT_DOUBLE_EQ(aggregated_relative_error()(ptr), 6.0 / 90.0);
  rows[0].scores.correct = true;
  rows[1].scores.correct = false;
  EXPECT_DOUBLE_EQ(proportion_correct()(ptr), 0.5);
}

}  // namespace
}  // namespace dtlab::report::detail
