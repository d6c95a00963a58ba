// Number formatting for the report; see format.h. snprintf with the "C"
// locale's conventions only ('.' decimal mark: dtlab never calls setlocale).
#include "analysis/report/detail/format.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "analysis/stats/apa.h"

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

std::string p_text(double p) {
  if (std::isnan(p)) return kDash;
  const std::string s = stats::apa_p_value(p);
  return s.rfind("= ", 0) == 0 ? s.substr(2) : s;
}

std::string bounded(double v, int decimals) { return std::isnan(v) ? kDash : stats::apa_bounded(v, decimals); }

std::string f_text(double f) {
  if (std::isnan(f)) return kDash;
  if (std::isinf(f)) return "∞";
  return fixed(f, 2);
}

std::string df_text(double df) {
  if (std::isnan(df)) return kDash;
  if (std::fabs(df - std::round(df)) < 1e-9) return printf_text("%.0f", df);
  return printf_text("%.2f", df);
}

std::string integer(long long v) { return std::to_string(v); }

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
