// Number formatting for the report; see format.h. snprintf with the "C"
// locale's conventions only ('.' decimal mark: dtlab never calls setlocale).
#include "analysis/report/detail/format.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace dtlab::report::detail {
namespace {

std::string printf_text(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

std::string fixed(double v, int decimals) {
  if (std::isnan(v)) return kDash;
  if (std::isinf(v)) return v > 0 ? "∞" : "−∞";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  // "-0.00" reads as a sign error; print "0.00".
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string mean_sd(double mean, double sd, int decimals) {
  return fixed(mean, decimals) + " (" + fixed(sd, decimals) + ")";
}

std::string p_text(double p, double log10_p) {
  if (std::isnan(p)) return kDash;
  if (p >= 1) return "1";
  if (p >= 1e-4) return printf_text("%.3g", p);
  std::string s;
  if (p > 0) {
    s = printf_text("%.2e", p);
  } else if (std::isfinite(log10_p)) {
    // p underflowed below the smallest double; its log is still exact.
    const double e = std::floor(log10_p);
    s = printf_text("%.2f", std::pow(10.0, log10_p - e)) + "e" + printf_text("%.0f", e);
  } else {
    return "0";
  }
  if (log10_p < -6 && std::isfinite(log10_p)) s += " (log10 p = " + printf_text("%.2f", log10_p) + ")";
  return s;
}

std::string p_short(double p, double log10_p) {
  if (p > 0 || std::isnan(p)) {
    const std::string full = p_text(p, log10_p);
    return full.substr(0, full.find(" (log10"));
  }
  return p_text(p, log10_p);
}

std::string f_text(double f) {
  if (std::isnan(f)) return kDash;
  if (std::isinf(f)) return "∞";
  return fixed(f, std::fabs(f) < 1 ? 3 : 2);
}

std::string df_text(double df) {
  if (std::isnan(df)) return kDash;
  if (std::fabs(df - std::round(df)) < 1e-9) return printf_text("%.0f", df);
  return printf_text("%.2f", df);
}

std::string integer(long long v) { return std::to_string(v); }

std::string counted(long long n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string percent(double share, int decimals) {
  if (std::isnan(share)) return kDash;
  return fixed(100 * share, decimals) + "%";
}

nlohmann::json num(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  return v;
}

std::string csv_number(double v) {
  if (std::isnan(v)) return "NA";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace dtlab::report::detail
