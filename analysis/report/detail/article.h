// The values the reference article reports (Elmqvist, Assarsson & Tsigas
// 2008, section VII: Table III, VII.2, VII.3), shown in an "article" column
// beside ours when the protocol has the reference design (design.h). They
// are labelled as the article's everywhere they appear and never enter a
// computation. Means (SD) over 16 participants, times in seconds.
#pragma once
#include <string>

namespace dtlab::report::detail::article {

struct Row {
  const char* scope;       // task id or "overall"
  double off_mean, off_sd; // standard (transparency off)
  double on_mean, on_sd;   // dynamic transparency (on)
  const char* F;           // as printed, F(1,15)
  const char* p;           // as printed
};

// Table III and VII.1 (overall).
inline constexpr Row kTime[] = {
    {"T1", 56.26, 38.72, 40.44, 20.99, "7.54", "< .05"},
    {"T2", 22.30, 16.20, 15.80, 10.21, "5.28", "< .05"},
    {"T3", 62.78, 35.63, 23.21, 12.01, "22.98", "< .01"},
    {"T4", 140.0, 61.75, 40.80, 24.16, "48.61", "< .01"},
    {"overall", 65.17, 27.75, 28.69, 11.02, "49.54", "< .001"},
};

// VII.2: relative error (the aggregated form), correctness, distance.
inline constexpr Row kAccuracy[] = {
    {"T1", 0.042, 0.046, 0.017, 0.018, "4.74", ".046"},
    {"T4", 0.123, 0.184, 0.034, 0.074, "4.12", ".061"},
    {"count", 0.100, 0.141, 0.027, 0.045, "6.28", ".024"},   // T1 and T4 combined
    {"T2", 0.963, 0.109, 0.963, 0.150, "—", "1.0 (Friedman)"},
    {"T3", 16.99, 14.44, 16.21, 8.88, ".068", ".797"},
};

// VII.3: ratings overall (0..4), Friedman p < .01; per scenario only "p < .05" (Fig. 10, no numbers).
inline constexpr Row kRatingOverall = {"overall", 1.52, 0.59, 3.09, 0.38, "—", "< .01 (Friedman)"};
inline constexpr double kPreference = 0.94, kPreferenceSd = 0.25;  // share preferring dynamic transparency
inline constexpr double kDepthTest = 2.94, kDepthTestSd = 0.25;    // of 3 pairs correct
inline constexpr double kDepthSelf = 2.75, kDepthSelfSd = 0.45;    // self-reported depth perception, 0..4

inline const Row* find(const Row* rows, size_t n, const std::string& scope) {
  for (size_t i = 0; i < n; ++i)
    if (scope == rows[i].scope) return &rows[i];
  return nullptr;
}

}  // namespace dtlab::report::detail::article
