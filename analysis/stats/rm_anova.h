// Repeated-measures ANOVA: one, two or n within-subject factors, optionally
// crossed with between-subject factors (mixed designs), as R's
// afex::aov_car(dv ~ between + Error(id/within)) / car::Anova(mlm, type = 3)
// compute it.
// Method (multivariate formulation of the univariate tests): the subject x
// cell matrix Y is transformed, for each within term S, by orthonormal
// contrasts M_S (Kronecker products of normalized Helmert contrasts, and of
// normalized means for factors outside S): Z = Y M_S'. Between factors enter
// as a full-factorial design X with sum-to-zero contrasts; B = (X'X)^-1 X'Z,
// E = residual sums of squares and products (p x p), H_T = B_T' V_TT^-1 B_T
// for each between term T (type III). Then
//   SS = tr H_T, SS_error = tr E, df1 = df_T p, df2 = (N - q) p, F = (SS/df1)/(SS_error/df2),
// with p = rows of M_S, N subjects, q = columns of X. Type III equals type I
// for balanced all-within designs.
// Sphericity (within terms with p >= 2), as car::summary.Anova.mlm:
//   GG = tr(E)^2 / (p tr(E^2));  HF = ((N - q + 1) p GG - 2) / (p (N - q - p GG)), may exceed 1;
//   p_gg uses df * GG, p_hf uses df * min(1, HF);
//   Mauchly: log W = log det E - p log(tr E / p), log det E = 2 sum log |R_jj|
//   from a Householder QR of the residual contrast scores (no cut-off, so a
//   nearly singular E keeps its tiny W); chi-square approximation with
//   Anderson's second term, n = N - q, including car/stats' use of the total
//   number of within cells (not p) in the "3 p" term of w2.
// Precision: the residual of each stratum (Y minus its between-cell means,
//   centred or averaged along each within factor) is formed in double-double
//   from the exact deltas, and the deltas are scaled by a power of two, so
//   residuals far below the effects keep their digits and nothing under- or
//   overflows short of a sum of squares beyond the double range (an Error).
// Cost: M_S is never formed: the contrast scores Y M_S' are applied factor by
//   factor (O(N C) per stratum), tr(E) is the scores' sum of squares and
//   tr(E^2) comes from the smaller Gram matrix (N x N or p x p); see the
//   size bound below.
// 1-df within terms: GG = HF = 1, Mauchly NaN. Between terms: sphericity NaN.
// Effect sizes (afex es = "pes", "ges"): eta_p2 = SS / (SS + SS_error);
//   eta_g2 = SS / (SS + sum of the distinct error SS of all strata, including
//   the between-subjects stratum [+ SS of effects with observed factors])
//   (Olejnik & Algina 2003; afex sums unique() error SS values, and so do we).
// Missing data: listwise deletion of subjects with a missing cell, with a
// warning naming them (detail/design.h); several rows per cell are an Error
// unless LongData::aggregate asks for their mean or median.
// Defined results: zero error SS (at most twice the rounding error of the
// input in norm, which is 0 for exact data such as integers, or below the
// double-double floor 1e-60 x the total sum of squares) -> F = +inf, p = 0 if
// SS > 0, else F = p = NaN; sphericity then NaN and p_gg = p_hf = p. One subject (or
// N = q) -> df2 = 0, F = p = NaN. Error df < p -> Mauchly W = 0, p NaN.
// Error df = 1 (e.g. two subjects) -> GG = 1/p exactly, HF = 0/0 = NaN.
// A factor with one level: its effects are left out with a warning.
// Where we knowingly differ from R: car/afex give a huge finite F (or stop)
// where the error SS is rounding noise of the input; we report it as exactly
// 0 (above). Where the residual is real but tiny beside the effects (data of
// size 2.5e14, SS_error 163/6), R's aov/car lose digits and we do not.
// Post-hoc comparisons (posthoc.h) cover within factors only (emmeans
// contrasts in mixed designs). Values whose sums of squares fall below the
// smallest normal double (data near 1e-160 and smaller) keep F, p and the
// effect sizes, computed on the scaled deltas; SS, SS_error and MSE are then
// printed rounded (0 or subnormal) with a warning (anova.h underflow_warning).
// References: car 3.x summary.Anova.mlm; afex anova.afex_aov; Maxwell &
// Delaney (2004) ch. 11-12, 14; Huynh & Feldt (1976); Mauchly (1940).
// Validated against: Maxwell & Delaney Table 12.1 (published F and SS; car
// conventions for GG/HF/Mauchly); R ez::ezANOVA via statsmodels tests;
// JAMOVI/ezANOVA via pingouin tests; afex 1.x obk.long values (mixed); exact
// rational arithmetic and car 3.1-1 for the nearly singular and tiny-residual
// cases (test_edge_cases.cpp). Each row also carries MSE, corrected df and
// the eta_p2 interval (effect_size.h).
// Usage: auto r = rm_anova(*long_data_from_csv(table, {"rt", "id", {"angle", "noise"}, {}}));
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "analysis/stats/anova.h"
#include "analysis/stats/descriptives.h"
#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats {

struct RmAnovaOptions {
  std::vector<std::string> observed;  // measured (not manipulated) factors, for eta_g2 (afex `observed`)
};

struct CellSummary {
  std::vector<std::pair<std::string, std::string>> levels;  // (factor, level), between factors first
  Descriptives d;                                           // over subjects (cell means)
};

struct RmAnovaResult {
  std::vector<std::string> within, between;  // factor names
  std::vector<Effect> effects;               // car order: for each within term (none, A, B, A:B, ...), each between term
  size_t n_subjects = 0;                     // subjects used
  std::vector<std::string> dropped_subjects; // removed by listwise deletion
  std::vector<CellSummary> cells;
  std::vector<std::string> warnings;
};

// data.subject must name the subject of every row; data.within / data.between
// give the factors. Input problems (between level changing within a subject,
// empty between cell, no complete subject) are Errors, and so is a design
// whose work exceeds kRmAnovaWorkBound (the message names the term and sizes).
Result<RmAnovaResult> rm_anova(const LongData& data, const RmAnovaOptions& options = {});

// The size bound: rm_anova's sphericity statistics of a within term with p
// contrasts cost about N p min(N, p) multiply-adds (the smaller Gram matrix of
// its residual scores; Mauchly's QR when N > p); everything else is O(N C).
// rm_anova_work sums that over the within terms (levels: of each within
// factor); above kRmAnovaWorkBound (about ten seconds of CPU on the
// development machine) rm_anova refuses. 3 subjects x 3000 levels: 2.7e7
// (0.05 s); 1500 x 1000: 1.5e9 (2.5 s); 2000 x 2000: 8e9 (about 20 s: refused).
inline constexpr double kRmAnovaWorkBound = 4e9;
double rm_anova_work(size_t subjects, const std::vector<size_t>& within_levels);

}  // namespace dtlab::stats
