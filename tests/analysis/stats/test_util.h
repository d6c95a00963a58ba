// Helpers shared by the statistics tests: where the reference data live, the
// log relative error (LRE) of NIST StRD, and loading a CSV into LongData.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "analysis/stats/csv.h"
#include "analysis/stats/long_data.h"

namespace dtlab::stats::test {

inline std::string data_path(const std::string& name) {
  return std::string(DTLAB_SOURCE_DIR) + "/tests/analysis/data/" + name;
}

// NIST's log relative error: -log10(|x - c| / |c|), 15 when equal to the certified digits' precision.
inline double lre(double x, double certified) {
  if (x == certified) return 15.0;
  return std::min(15.0, -std::log10(std::fabs(x - certified) / std::fabs(certified)));
}

// Relative closeness for values compared with R / published numbers.
inline ::testing::AssertionResult near_rel(double actual, double expected, double rel) {
  if (std::fabs(actual - expected) <= rel * std::fabs(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << actual << " differs from " << expected << " by more than " << rel
                                       << " relative (" << std::fabs(actual - expected) / std::fabs(expected) << ")";
}

// True when `actual` rounds to the value printed as `text` (e.g. "0.961637",
// "3.905263e-04"): the tolerance is half a unit in the last printed digit.
inline ::testing::AssertionResult printed(double actual, const std::string& text) {
  const double expected = std::strtod(text.c_str(), nullptr);
  const size_t e = text.find_first_of("eE");
  const std::string mantissa = text.substr(0, e);
  const size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  const int exponent = e == std::string::npos ? 0 : std::atoi(text.c_str() + e + 1);
  const double tol = 0.5 * std::pow(10.0, exponent - decimals) * (1 + 1e-9);
  if (std::fabs(actual - expected) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << actual << " does not round to the printed " << text;
}

// Loads data/<name> in long format; fails the test on a CSV error.
inline LongData load_long(const std::string& name, const ColumnRoles& roles) {
  auto t = read_csv_file(data_path(name));
  EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().to_string());
  auto d = long_data_from_csv(*t, roles);
  EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error().to_string());
  return *d;
}

// Builds LongData from CSV text (tests of hard cases written inline).
inline LongData long_from_text(const std::string& text, const ColumnRoles& roles) {
  auto t = parse_csv(text, "inline.csv");
  EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().to_string());
  auto d = long_data_from_csv(*t, roles);
  EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error().to_string());
  return *d;
}

}  // namespace dtlab::stats::test
