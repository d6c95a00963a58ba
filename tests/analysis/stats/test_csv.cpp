// CSV reading and exact decimal parsing: RFC 4180 details, errors that name
// file, line and column, missing-value tokens, and decimal differences that
// are exact where binary doubles are not.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <string>

#include "analysis/stats/csv.h"
#include "analysis/stats/long_data.h"
#include "analysis/stats/measurements.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

TEST(Csv, ReadsQuotesCrlfBomAndBlankLines) {
  auto t = parse_csv("\xEF\xBB\xBFid, \"name, with comma\" ,v\r\n1,\"say \"\"hi\"\"\",2.5\r\n\r\n2,\"two\nlines\",3\n", "x.csv");
  ASSERT_TRUE(t.ok()) << t.error().to_string();
  ASSERT_EQ(t->header.size(), 3u);
  EXPECT_EQ(t->header[1], "name, with comma");
  ASSERT_EQ(t->rows.size(), 2u);
  EXPECT_EQ(t->rows[0][1], "say \"hi\"");
  EXPECT_EQ(t->rows[1][1], "two\nlines");
  EXPECT_EQ(t->line[0], 2);
  EXPECT_EQ(t->line[1], 4) << "blank line 3 is skipped but counted";
}

TEST(Csv, RowWithWrongFieldCountNamesItsLine) {
  auto t = parse_csv("a,b\n1,2\n3\n", "bad.csv");
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().file, "bad.csv");
  EXPECT_EQ(t.error().line, 3);
  EXPECT_NE(t.error().message.find("expected 2 fields"), std::string::npos);
}

TEST(Csv, UnclosedQuoteAndDuplicateColumnAreErrors) {
  EXPECT_FALSE(parse_csv("a,b\n\"1,2\n", "q.csv").ok());
  auto dup = parse_csv("a,a\n1,2\n", "d.csv");
  ASSERT_FALSE(dup.ok());
  EXPECT_EQ(dup.error().field, "a");
  EXPECT_FALSE(read_csv_file("/nonexistent/dir/x.csv").ok());
}

struct BadCell {
  const char* text;
  const char* needle;
};

TEST(LongData, TextNaNAndInfInTheDvAreRejectedWithLineAndColumn) {
  for (const BadCell& c : {BadCell{"abc", "found 'abc'"}, BadCell{"NaN", "NaN and Inf are not accepted"},
                           BadCell{"inf", "NaN and Inf are not accepted"}, BadCell{"1,5", "found '1,5'"},
                           BadCell{"1.2.3", "found '1.2.3'"}, BadCell{"0x10", "found '0x10'"}}) {
    SCOPED_TRACE(c.text);
    const std::string csv = std::string("id,cond,rt\n1,a,400\n1,b,\"") + c.text + "\"\n";
    auto t = parse_csv(csv, "study.csv");
    ASSERT_TRUE(t.ok());
    auto d = long_data_from_csv(*t, {"rt", "id", {"cond"}, {}});
    ASSERT_FALSE(d.ok());
    EXPECT_EQ(d.error().file, "study.csv");
    EXPECT_EQ(d.error().line, 3);
    EXPECT_EQ(d.error().column, 3);
    EXPECT_EQ(d.error().field, "rt");
    EXPECT_NE(d.error().message.find(c.needle), std::string::npos) << d.error().message;
  }
}

TEST(LongData, EmptyAndNaAreMissingAndUnknownColumnsAreNamed) {
  auto t = parse_csv("id,cond,rt\n1,a,\n1,b,NA\n2,a,3\n", "m.csv");
  ASSERT_TRUE(t.ok());
  auto d = long_data_from_csv(*t, {"rt", "id", {"cond"}, {}});
  ASSERT_TRUE(d.ok()) << d.error().to_string();
  EXPECT_TRUE(d->dv.missing(0));
  EXPECT_TRUE(d->dv.missing(1));
  EXPECT_EQ(d->dv.value[2], 3.0);
  auto bad = long_data_from_csv(*t, {"time", "id", {"cond"}, {}});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().field, "time");
  EXPECT_NE(bad.error().message.find("id, cond, rt"), std::string::npos);
  auto empty_id = parse_csv("id,cond,rt\n,a,1\n", "e.csv");
  EXPECT_FALSE(long_data_from_csv(*empty_id, {"rt", "id", {"cond"}, {}}).ok());
}

TEST(LongData, WideRowsBecomeSubjectsAndEmptyCellsMissing) {
  auto t = parse_csv("A,B,C\n1,2,3\n4,,6\n", "w.csv");
  ASSERT_TRUE(t.ok());
  WideRoles roles;
  roles.factor = "time";
  auto d = long_data_from_wide_csv(*t, roles);
  ASSERT_TRUE(d.ok()) << d.error().to_string();
  ASSERT_EQ(d->rows(), 6u);
  EXPECT_EQ(d->subject[0], "line 2");
  EXPECT_EQ(d->subject[4], "line 3");
  EXPECT_EQ(d->within[0].name, "time");
  EXPECT_EQ(d->within[0].level[4], "B");
  EXPECT_TRUE(d->dv.missing(4));
}

TEST(Decimal, ParsesTheGrammarAndRejectsTheRest) {
  for (const char* ok : {"0", "-0", "+3", "12.5", ".5", "5.", "1e-3", "-2.5E+10", " 7 ", "0001.2300"}) {
    SCOPED_TRACE(ok);
    const auto d = parse_decimal(ok);
    ASSERT_TRUE(d.has_value());
    std::string s = ok;
    while (!s.empty() && s.front() == ' ') s.erase(0, 1);
    while (!s.empty() && s.back() == ' ') s.pop_back();
    if (s.front() == '+') s.erase(0, 1);
    double ref = 0;
    std::from_chars(s.data(), s.data() + s.size(), ref);
    EXPECT_EQ(d->value, ref) << "value must be the correctly rounded double";
  }
  for (const char* bad : {"", "abc", "nan", "inf", "1e", "--1", "1.2.3", "0x10", "1,5", "1e5x", ".", "e3"}) {
    SCOPED_TRACE(bad);
    EXPECT_FALSE(parse_decimal(bad).has_value());
  }
}

TEST(Decimal, DifferencesAreExactOnTheDigits) {
  // 1000000000000.4 - 1000000000000.3 is exactly 0.1: the double 0.1, not the
  // 0.10009765625 that subtracting the two nearest doubles gives.
  const auto a = *parse_decimal("1000000000000.4");
  const auto b = *parse_decimal("1000000000000.3");
  EXPECT_EQ(decimal_difference(a, b), 0.1);
  EXPECT_NE(a.value - b.value, 0.1);
  EXPECT_EQ(decimal_difference(*parse_decimal("107.8681568"), *parse_decimal("107.8681465")), 1.03e-5);
  EXPECT_EQ(decimal_difference(*parse_decimal("-1.5e3"), *parse_decimal("2.5")), -1502.5);
  // beyond 38 significant digits the value is rounded, the difference stays close
  const auto long1 = *parse_decimal("1.000000000000000000000000000000000000000000001");
  EXPECT_FALSE(long1.exact);
  EXPECT_EQ(long1.value, 1.0);
}

TEST(Measurements, OffsetIsAnInputValueNearTheMean) {
  std::vector<std::optional<Decimal>> v{parse_decimal("1000000000000.4"), parse_decimal("1000000000000.3"),
                                        std::nullopt, parse_decimal("1000000000000.5")};
  const Measurements m = Measurements::from_decimals(v);
  EXPECT_EQ(m.offset, parse_decimal("1000000000000.4")->value);
  EXPECT_EQ(m.delta[0], 0.0);
  EXPECT_EQ(m.delta[1], -0.1);
  EXPECT_EQ(m.delta[3], 0.1);
  EXPECT_TRUE(m.missing(2));
}

}  // namespace
}  // namespace dtlab::stats
