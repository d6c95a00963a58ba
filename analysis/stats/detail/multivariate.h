// The multivariate model of a mixed design as emmeans sees an afex fit
// (afex_options(emmeans_model = "multivariate"), afex's default): every
// subject's vector of cell values regressed on the full-factorial between
// design, one residual covariance Sigma pooled over the q between cells with
// N - q df. Marginal means average the between cells and the within cells
// with equal weights (emmeans' default), so groups of unequal size count
// alike. A contrast is a weight vector per factor (between factors first,
// then within, in CellDesign order); its weights over cells are the products.
//   estimate = sum_g a_g sum_c w_c mean_gc,  var = (w' Sigma w) sum_g a_g^2 / n_g,
//   t = estimate / SE on N - q df (emmeans' pairs / contrast);
//   several contrasts: F = est' V^-1 est / r on (r, N - q) df (emmeans'
//   joint_tests / test(joint = TRUE), a Wald F, not Hotelling's).
// Deltas are scaled by a power of two before any square, so values near the
// double range keep their precision; estimates and SEs come back unscaled.
// Never reads the LongData again; Errors only for a between cell without a
// subject (as rm_anova) or no error df.
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/posthoc.h"
#include "study/common/error.h"

namespace dtlab::stats::detail {

using FactorWeights = std::vector<std::vector<double>>;  // per factor (between, then within), per level

struct ContrastEstimate {
  double estimate = 0, se = 0, df = 0;
  double sd = 0;  // sqrt(w' Sigma w): the pooled within-group SD of the subjects' contrast scores
};

struct JointTest {
  double F = 0, df1 = 0, df2 = 0;
};

// Valid while the CellDesign it was fitted on is.
class MultivariateModel {
 public:
  // Requires every combination of between levels to have a subject.
  static Result<MultivariateModel> fit(const CellDesign& d, const std::string& source);

  double error_df() const { return dfe_; }
  size_t subjects() const { return cell_of_.size(); }
  size_t factors() const { return between_levels_.size() + within_levels_.size(); }
  size_t levels(size_t factor) const;                      // levels of factor (between first, then within)
  const std::string& label(size_t factor, size_t level) const;  // between: the levels some kept subject has
  const std::string& name(size_t factor) const;

  // One contrast (weights as above).
  ContrastEstimate estimate(const FactorWeights& w) const;
  // Several contrasts at once (linearly independent); F NaN where V is singular.
  JointTest joint(const std::vector<FactorWeights>& rows) const;

  // Equal weights 1/L on every level of every factor: the grand mean (set the factors a contrast is about).
  FactorWeights averaging() const;
  // emmeans' pairs() row for level i - level j of `factor`, with `w` weighting the other factors:
  // test "emmeans t", n = subjects, df = N - q, 95% CI, d_z = estimate / sd.
  Comparison pair(size_t factor, size_t i, size_t j, FactorWeights w) const;
  // The joint F of `factor`'s levels (each against the last), with `w` weighting the others.
  JointTest levels_differ(size_t factor, const FactorWeights& w) const;

 private:
  const CellDesign* d_ = nullptr;
  std::vector<size_t> between_levels_, within_levels_;
  std::vector<std::vector<std::string>> between_labels_;  // surviving levels, renumbered in first-appearance order
  std::vector<size_t> cell_of_;  // between cell of each subject (mixed radix of its levels, first factor slowest)
  std::vector<double> n_;        // subjects per between cell
  double dfe_ = 0;
  int exponent_ = 0;             // deltas are scaled by 2^-exponent_

  // Per contrast: between-cell weights a, and the subjects' scores x_s = sum_c w_c Y_sc (scaled).
  void scores(const FactorWeights& w, std::vector<double>& a, std::vector<double>& x) const;
};

}  // namespace dtlab::stats::detail
