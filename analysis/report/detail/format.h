// Numbers as the report prints them, and as report.json stores them. Text:
// fixed decimals, "—" for undefined values; p-values in APA style (".002",
// "< .001", "> .999"; analysis/stats/apa.h), statistics bounded by 1 (eta
// squared, epsilon, W) without a leading zero. Rounding is for text only:
// JSON and CSV keep round-trip doubles, NaN as null, infinities as
// "Infinity"/"-Infinity" (the convention of `dtlab stats`).
// Pure functions; never locale-dependent.
#pragma once
#include <nlohmann/json.hpp>

#include <limits>
#include <string>

#include "study/common/text.h"  // dtlab::count: "1 trial", "3 trials"

namespace dtlab::report::detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();  // "not computed" in a result

inline constexpr const char* kDash = "—";  // undefined value in a table

std::string fixed(double v, int decimals);            // "12.35"; kDash for NaN; "∞"/"−∞" for infinities
std::string mean_sd(double mean, double sd, int decimals);  // "56.26 (38.72)"; sd NaN -> "56.26 (—)"
std::string p_text(double p);                         // a table cell: ".024", "< .001", "> .999"; kDash for NaN
std::string bounded(double v, int decimals = 2);      // ".57", "1.00", "-.12"; kDash for NaN (eta², ε, W, r)
std::string f_text(double f);                         // F with 2 decimals (APA), "∞", kDash for NaN
std::string df_text(double df);                       // "15" or "12.47" (GG-corrected df)
std::string integer(long long v);
std::string percent(double share, int decimals = 1);  // 0.125 -> "12.5%"

nlohmann::json num(double v);        // NaN -> null, +-inf -> "Infinity"/"-Infinity"
std::string csv_number(double v);  // shortest round-trip text; "NA" for NaN, "Inf"/"-Inf" (R's spelling)

}  // namespace dtlab::report::detail
