// Repeated-measures correlation (Bland & Altman 1995; Bakdash & Marusich
// 2017, R package rmcorr): the common within-group association of two
// measures, removing every group's own mean (an ANCOVA with the group as a
// factor and parallel slopes). Here a group is a participant (or a
// participant x condition), so between-participant differences in speed
// cannot masquerade as a speed-accuracy relation.
//   x, y centred within each group; r = Sxy / sqrt(Sxx Syy); slope = Sxy / Sxx
//   df = N - G - 1 (N pairs, G groups with at least one pair)
//   t = r sqrt(df / (1 - r^2)), p = two-sided Student t (analysis/stats)
//   95% CI: tanh(atanh(r) -+ z_0.975 / sqrt(df - 1)) (rmcorr >= 0.6)
// Missing data: pairs with a NaN are dropped; groups with one pair add
// nothing but still count in G as rmcorr counts them. Undefined (NaN with
// df reported) when Sxx or Syy is 0 or df < 1.
// Validated against: rmcorr 0.6/0.7 on bland1995 (r = -0.5067697, df = 38,
// p = 0.0008471081, CI -0.7067146 -0.2318631), tests/analysis/report.
#pragma once
#include <string>
#include <vector>

namespace dtlab::report::detail {

struct RmCorr {
  size_t n = 0, groups = 0;
  double r = 0, df = 0, t = 0, p = 0, log10_p = 0, ci_low = 0, ci_high = 0;
  double slope = 0;  // within-group regression of y on x
};

// group[i] names the group of pair (x[i], y[i]).
RmCorr rm_corr(const std::vector<std::string>& group, const std::vector<double>& x, const std::vector<double>& y);

}  // namespace dtlab::report::detail
