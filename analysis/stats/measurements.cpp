// Exact decimal parsing and differences; see measurements.h.
#include "analysis/stats/measurements.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

namespace dtlab::stats {
namespace {

constexpr int kMaxDigits = 38;  // 10^38 < 2^128

uint128 pow10_128(int n) {
  uint128 r = 1;
  for (int i = 0; i < n; ++i) r *= 10;
  return r;
}

std::string to_decimal_string(uint128 v) {
  if (v == 0) return "0";
  std::string s;
  while (v > 0) {
    s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(v % 10)));
    v /= 10;
  }
  return s;
}

// (-1)^neg * mag * 10^exp rounded once to double.
double round_to_double(uint128 mag, int exp, bool neg) {
  static const double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                  1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  double r;
  if (mag < (static_cast<uint128>(1) << 53) && exp >= -22 && exp <= 22) {
    // Both operands are exact doubles, so one IEEE operation rounds once.
    const double m = static_cast<double>(static_cast<unsigned long long>(mag));
    r = exp >= 0 ? m * kPow10[exp] : m / kPow10[-exp];
  } else {
    const std::string s = to_decimal_string(mag) + "e" + std::to_string(exp);
    r = 0.0;
    const auto res = std::from_chars(s.data(), s.data() + s.size(), r);  // correctly rounded
    if (res.ec == std::errc::result_out_of_range) r = exp > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  return neg ? -r : r;
}

// Whether mag * 10^exp is a double exactly: mag * 10^exp = odd * 2^k with
// odd < 2^53 (and inside the exponent range, which |exp| <= 300 keeps).
bool representable(uint128 mag, int exp) {
  if (mag == 0) return true;
  if (exp > 300 || exp < -300) return false;
  uint128 m = mag;
  if (exp >= 0) {
    for (int i = 0; i < exp; ++i) {
      if (m > (~static_cast<uint128>(0)) / 5) return false;
      m *= 5;
    }
  } else {
    for (int i = 0; i < -exp; ++i) {
      if (m % 5 != 0) return false;
      m /= 5;
    }
  }
  while ((m & 1) == 0) m >>= 1;
  return m < (static_cast<uint128>(1) << 53);
}

double difference_rounded(uint128 mag, int exp, bool neg, bool* exact) {
  if (exact) *exact = representable(mag, exp);
  return round_to_double(mag, exp, neg);
}

// Rounding error of a - b in double, known exactly (TwoSum).
double subtraction_error(double a, double b) {
  const double s = a - b;
  const double bb = s - a;
  return std::fabs((a - (s - bb)) + (-b - bb));
}

// Mean of the finite values without overflow (sum of v / n), for choosing the offset only.
double safe_mean(const std::vector<double>& v, size_t n) {
  double m = 0.0;
  for (double x : v)
    if (!std::isnan(x)) m += x / static_cast<double>(n);
  return m;
}

}  // namespace

std::optional<Decimal> parse_decimal(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  if (s.empty()) return std::nullopt;

  Decimal d;
  size_t i = 0;
  if (s[i] == '+' || s[i] == '-') {
    d.negative = s[i] == '-';
    ++i;
  }
  int digits_seen = 0, significant = 0, dropped_exp = 0, frac_digits = 0;
  bool round_up = false, in_fraction = false;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '.') {
      if (in_fraction) return std::nullopt;
      in_fraction = true;
      continue;
    }
    if (c < '0' || c > '9') break;
    ++digits_seen;
    if (in_fraction) ++frac_digits;
    if (significant == 0 && c == '0') continue;  // leading zeros
    if (significant < kMaxDigits) {
      d.magnitude = d.magnitude * 10 + static_cast<unsigned>(c - '0');
      ++significant;
    } else {
      if (significant == kMaxDigits && dropped_exp == 0) round_up = c >= '5';
      if (c != '0') d.exact = false;
      ++dropped_exp;  // digit beyond 38 significant ones: scale instead of storing
    }
  }
  if (digits_seen == 0) return std::nullopt;
  long long exp10 = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
      eneg = s[i] == '-';
      ++i;
    }
    const size_t start = i;
    for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i)
      if (exp10 < 100000) exp10 = exp10 * 10 + (s[i] - '0');
    if (i == start) return std::nullopt;
    if (eneg) exp10 = -exp10;
  }
  if (i != s.size()) return std::nullopt;
  if (round_up) ++d.magnitude;  // magnitude < 10^38 + 1 still fits
  d.exponent = static_cast<int>(exp10 - frac_digits + dropped_exp);

  const char* first = s.data();
  auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), d.value);
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(d.value)) {
    // from_chars rejects a leading '+'; retry without it.
    if (s.front() == '+') {
      auto r2 = std::from_chars(first + 1, s.data() + s.size(), d.value);
      if (r2.ec != std::errc() || r2.ptr != s.data() + s.size() || !std::isfinite(d.value)) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  if (d.magnitude == 0) d.exponent = 0;
  return d;
}

double decimal_difference(const Decimal& a, const Decimal& b, bool* exact) {
  auto fallback = [&] {
    if (exact) *exact = a.exact && b.exact && subtraction_error(a.value, b.value) == 0.0;
    return a.value - b.value;
  };
  if (!a.exact || !b.exact) return fallback();
  if (a.magnitude == 0) return difference_rounded(b.magnitude, b.exponent, !b.negative, exact);
  if (b.magnitude == 0) return difference_rounded(a.magnitude, a.exponent, a.negative, exact);
  const int e = std::min(a.exponent, b.exponent);
  const int sa = a.exponent - e, sb = b.exponent - e;
  const uint128 max = ~static_cast<uint128>(0) >> 2;  // keep one bit of headroom for the sum
  if (sa > kMaxDigits || sb > kMaxDigits) return fallback();
  const uint128 pa = pow10_128(sa), pb = pow10_128(sb);
  if (a.magnitude > max / pa || b.magnitude > max / pb) return fallback();
  const uint128 A = a.magnitude * pa, B = b.magnitude * pb;
  // signed A - B with magnitudes: compute |A -+ B| and its sign.
  if (a.negative == b.negative) {
    if (A >= B) return difference_rounded(A - B, e, a.negative, exact);
    return difference_rounded(B - A, e, !a.negative, exact);
  }
  return difference_rounded(A + B, e, a.negative, exact);
}

namespace {

unsigned digits_of(uint128 v) {
  unsigned d = 0;
  for (; v > 0; v /= 10) ++d;
  return d;
}

constexpr unsigned kMeanDigits = 37;  // kept digits of a mean; a 38th marks an inexact rest

// The first kMeanDigits significant digits of sum * 10^exp / n, with a sticky 1 digit if more follow.
Decimal truncated_quotient(uint128 sum, int exp, bool negative, uint128 n) {
  Decimal d;
  d.negative = negative;
  uint128 q = sum / n, r = sum % n;
  bool sticky = false;
  const unsigned have = digits_of(q);
  if (have > kMeanDigits) {
    const uint128 cut = pow10_128(static_cast<int>(have - kMeanDigits));
    sticky = q % cut != 0 || r != 0;
    q /= cut;
    exp += static_cast<int>(have - kMeanDigits);
    r = 0;
  }
  while (r != 0 && digits_of(q) < kMeanDigits) {  // long division, one digit at a time (r < n, so 10 r fits)
    r *= 10;
    q = q * 10 + r / n;
    r %= n;
    --exp;
  }
  sticky = sticky || r != 0;
  if (sticky) {
    q = q * 10 + 1;
    --exp;
  }
  d.magnitude = q;
  d.exponent = q == 0 ? 0 : exp;
  d.exact = !sticky;
  d.value = round_to_double(d.magnitude, d.exponent, d.negative);
  return d;
}

// Exact order of two decimals on their digits (the double difference where they cannot be aligned).
bool decimal_less(const Decimal& a, const Decimal& b) {
  Decimal x = a, y = b;
  x.exact = y.exact = true;
  return decimal_difference(x, y) < 0;
}

}  // namespace

std::optional<Decimal> decimal_mean(const std::vector<Decimal>& xs) {
  if (xs.empty()) return std::nullopt;
  int e = std::numeric_limits<int>::max();  // the smallest exponent of a nonzero value
  for (const auto& x : xs) {
    if (!x.exact) return std::nullopt;
    if (x.magnitude != 0) e = std::min(e, x.exponent);
  }
  if (e == std::numeric_limits<int>::max()) e = 0;  // every value is zero
  uint128 pos = 0, neg = 0;
  for (const auto& x : xs) {
    if (x.magnitude == 0) continue;
    const int shift = x.exponent - e;
    if (shift > kMaxDigits) return std::nullopt;
    uint128 m = 0;
    if (__builtin_mul_overflow(x.magnitude, pow10_128(shift), &m)) return std::nullopt;
    uint128& acc = x.negative ? neg : pos;
    if (__builtin_add_overflow(acc, m, &acc)) return std::nullopt;
  }
  const bool negative = neg > pos;
  return truncated_quotient(negative ? neg - pos : pos - neg, e, negative, static_cast<uint128>(xs.size()));
}

std::optional<Decimal> decimal_median(std::vector<Decimal> xs) {
  if (xs.empty()) return std::nullopt;
  std::sort(xs.begin(), xs.end(), decimal_less);
  const size_t h = xs.size() / 2;
  if (xs.size() % 2) return xs[h];
  return decimal_mean({xs[h - 1], xs[h]});
}

void Measurements::describe(const Decimal& x, double& v, double& d, double& n) const {
  Decimal a = x, b = offset_decimal;
  a.exact = b.exact = true;  // difference on the digits kept (a mean's are its first 37)
  bool exact = false;
  v = x.value;
  d = decimal_difference(a, b, &exact);
  exact = exact && x.exact && offset_decimal.exact;
  n = exact ? 0.0 : std::ldexp(std::fabs(d), -53) + std::fabs(v) * 1e-36 + std::numeric_limits<double>::denorm_min();
}

bool Measurements::missing(size_t i) const { return std::isnan(value[i]); }

Measurements Measurements::from_doubles(std::vector<double> values) {
  Measurements m;
  size_t n = 0;
  for (double v : values) n += std::isnan(v) ? 0 : 1;
  if (n > 0) {
    const double mean = safe_mean(values, n);
    double best = std::numeric_limits<double>::infinity();
    bool found = false;
    for (double v : values)
      if (!std::isnan(v) && (!found || std::fabs(v - mean) < best)) {
        best = std::fabs(v - mean);
        m.offset = v;
        found = true;
      }
  }
  m.delta.resize(values.size());
  m.noise.resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    m.delta[i] = values[i] - m.offset;  // NaN stays NaN
    m.noise[i] = std::isnan(values[i]) ? values[i] : subtraction_error(values[i], m.offset);
  }
  m.value = std::move(values);
  return m;
}

Measurements Measurements::from_decimals(const std::vector<std::optional<Decimal>>& values) {
  Measurements m;
  const size_t n = values.size();
  m.value.assign(n, std::numeric_limits<double>::quiet_NaN());
  m.delta.assign(n, std::numeric_limits<double>::quiet_NaN());
  m.noise.assign(n, std::numeric_limits<double>::quiet_NaN());
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    if (values[i]) {
      m.value[i] = values[i]->value;
      ++count;
    }
  if (count == 0) return m;
  const double mean = safe_mean(m.value, count);
  size_t ref = n;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i)
    if (values[i] && (ref == n || std::fabs(values[i]->value - mean) < best)) {
      best = std::fabs(values[i]->value - mean);
      ref = i;
    }
  m.offset = values[ref]->value;
  m.offset_decimal = *values[ref];
  m.decimal.resize(n);
  for (size_t i = 0; i < n; ++i)
    if (values[i]) {
      bool exact = false;
      m.decimal[i] = *values[i];
      m.delta[i] = decimal_difference(*values[i], *values[ref], &exact);
      // Inexact: the one rounding of the exact difference, at most half an ulp
      // (and at least half the smallest subnormal, where ulps stop shrinking).
      m.noise[i] = exact ? 0.0 : std::max(std::ldexp(std::fabs(m.delta[i]), -53),
                                          std::numeric_limits<double>::denorm_min());
    }
  return m;
}

}  // namespace dtlab::stats
