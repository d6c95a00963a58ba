// Numbers as the report prints them, and as report.json stores them. Text:
// fixed decimals, "—" for undefined values; p-values exact (3 significant
// digits, scientific below 1e-4, with log10 p below 1e-6 so that p-values
// that underflow stay readable). JSON: round-trip doubles, NaN as null,
// infinities as "Infinity"/"-Infinity" (the convention of `dtlab stats`).
// Pure functions; never locale-dependent.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace dtlab::report::detail {

inline constexpr const char* kDash = "—";  // undefined value in a table

std::string fixed(double v, int decimals);            // "12.35"; kDash for NaN; "∞"/"−∞" for infinities
std::string mean_sd(double mean, double sd, int decimals);  // "56.26 (38.72)"; sd NaN -> "56.26 (—)"
std::string p_text(double p, double log10_p);         // "0.0240", "3.91e-05", "2.1e-12 (log10 p = -11.68)"
std::string p_short(double p, double log10_p);        // the same without the log10 part, for narrow table cells
                                                      // (kept when p underflowed: "6.31e-346 (log10 p = -345.20)")
std::string f_text(double f);                         // F with 2 decimals (3 below 1)
std::string df_text(double df);                       // "15" or "12.47" (GG-corrected df)
std::string integer(long long v);
std::string percent(double share, int decimals = 1);  // 0.125 -> "12.5%"
// A count with its noun in agreement: counted(1, "trial") = "1 trial", counted(3, "trial") = "3 trials".
std::string counted(long long n, const std::string& noun);

nlohmann::json num(double v);
std::string csv_number(double v);  // shortest round-trip text; "NA" for NaN, "Inf"/"-Inf" (R's spelling)  // NaN -> null, +-inf -> "Infinity"/"-Infinity"

}  // namespace dtlab::report::detail
