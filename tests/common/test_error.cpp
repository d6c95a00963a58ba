// Error messages name file, line, column and field in a fixed order.
#include <gtest/gtest.h>

#include "study/common/error.h"

namespace {

TEST(Error, FormatsEveryPartPresent) {
  dtlab::Error e{"p.toml", 12, 5, "factors.scenario", "expected an array of strings"};
  EXPECT_EQ(e.to_string(), "p.toml:12:5: factors.scenario: expected an array of strings");
}

TEST(Error, LeavesOutMissingParts) {
  EXPECT_EQ((dtlab::Error{"", 0, 0, "", "boom"}).to_string(), "boom");
  EXPECT_EQ((dtlab::Error{"f.csv", 3, 0, "", "NaN"}).to_string(), "f.csv:3: NaN");
}

TEST(Diagnostic, SaysSeverity) {
  dtlab::Diagnostic d{dtlab::Severity::warning, {"p.toml", 2, 1, "participants", "not a multiple of 4"}};
  EXPECT_EQ(d.to_string(), "p.toml:2:1: warning: participants: not a multiple of 4");
}

TEST(Result, HoldsValueOrError) {
  dtlab::Result<int> a = 3;
  dtlab::Result<int> b = dtlab::Error{"x", 1, 0, "", "bad"};
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(*a, 3);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error().line, 1);
}

}  // namespace
