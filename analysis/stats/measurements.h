// Numbers for the statistics, kept accurate when they share many leading
// digits (NIST StRD SmLs07-09: 1000000000000.4, ...). Each value is stored
// twice: `value`, the correctly rounded double of its decimal text (what R or
// any strtod-based reader holds), and `delta` = value - offset, where the
// offset is one of the values and the difference is taken EXACTLY on the
// decimal digits, then rounded once. Sums of squares are computed from the
// deltas, so the constant leading digits never enter floating point.
// Guarantees: delta is exact to 1/2 ulp of itself for decimal inputs with up to
// 38 significant digits; value is bit-identical to std::from_chars. Missing
// values are NaN in both. Means of decimals (decimal_mean) are taken on the
// digits, so means that are equal as decimals are equal doubles (R's mean()
// keeps 0.2 and mean(c(0.1, 0.2, 0.3)) equal; a plain sum / n does not).
// Never throws for bad text: parse_decimal says no.
// Usage: auto m = decimal_mean({*parse_decimal("0.1"), *parse_decimal("0.3")});  // m->value == 0.2
#pragma once
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace dtlab::stats {

__extension__ typedef unsigned __int128 uint128;

// A decimal number as written: (-1)^negative * magnitude * 10^exponent.
struct Decimal {
  uint128 magnitude = 0;
  int exponent = 0;
  bool negative = false;
  bool exact = true;   // false if the text had more than 38 significant digits (the rest were rounded)
  double value = 0.0;  // the correctly rounded double of the text
};

// Parses "[blanks][+|-]digits[.digits][(e|E)[+|-]digits][blanks]" (also ".5", "5.").
// Returns nullopt for anything else, including "NaN", "inf", "1,5", "" and
// numbers outside the double range.
std::optional<Decimal> parse_decimal(std::string_view text);

// a - b computed exactly on the decimal digits, then rounded once to double.
// Falls back to a.value - b.value only when the digits cannot be aligned in
// 128 bits (e.g. 1e30 - 1e-30), where that double difference is as accurate.
// *exact (if given) is set to whether the result equals a - b exactly.
double decimal_difference(const Decimal& a, const Decimal& b, bool* exact = nullptr);

// The mean of xs (none missing, at least one) taken exactly on the decimal
// digits: the exact sum over n, cut to its first 37 significant digits, with a
// 38th digit 1 when the rest is nonzero (so the result is a function of the
// mean's value alone: two means equal as rational numbers give the same
// Decimal), `exact` false then; `value` is that decimal rounded once to double.
// nullopt when an input has more than 38 digits or the digits cannot be
// aligned in 128 bits (e.g. 1e30 and 1e-30); callers then average the doubles.
std::optional<Decimal> decimal_mean(const std::vector<Decimal>& xs);

// The median of xs (none missing, at least one): the middle value, or the
// decimal_mean of the two middle values; ordered exactly on the digits.
std::optional<Decimal> decimal_median(std::vector<Decimal> xs);

// One numeric variable (e.g. the dependent variable, one entry per CSV row).
struct Measurements {
  double offset = 0.0;        // the reference value (one of the inputs), as a double
  std::vector<double> value;  // value[i]: correctly rounded input; NaN = missing
  std::vector<double> delta;  // delta[i]: input - offset, exact difference rounded once; NaN = missing
  std::vector<double> noise;  // noise[i]: bound on |delta[i] - (input - offset)|: 0 when delta is exact
                              // (integers, binary fractions); empty = unknown (callers assume half an ulp)
  std::vector<Decimal> decimal;  // decimal[i]: the parsed text (from_decimals only; empty otherwise)
  Decimal offset_decimal;        // the offset as parsed (from_decimals only)

  size_t size() const { return value.size(); }
  bool missing(size_t i) const;

  // From doubles (NaN = missing): delta = value - offset in double, which is
  // exact to 1/2 ulp of the difference of the doubles given (noise is that
  // rounding error, known exactly from TwoSum).
  static Measurements from_doubles(std::vector<double> values);
  // From parsed decimals (nullopt = missing): offset is the value nearest the
  // mean (the mean taken without overflow, values up to the double maximum),
  // deltas from decimal_difference(); a difference beyond the double range is
  // +-inf (callers report the overflow).
  static Measurements from_decimals(const std::vector<std::optional<Decimal>>& values);

  // The value, delta and noise of a number given as a Decimal (e.g. a mean of
  // rows), with delta taken on the digits against offset_decimal; requires
  // `decimal` to be filled.
  void describe(const Decimal& x, double& value, double& delta, double& noise) const;
};

}  // namespace dtlab::stats
