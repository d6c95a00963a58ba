// From a long-format table to the subject x cell matrix every repeated-
// measures test starts from. Policy (documented in README "Statistics"):
// levels and subjects keep their order of first appearance; several rows for
// one subject and cell are an Error naming both lines unless the data ask for
// an aggregation (LongData::aggregate: mean or median, as afex's
// fun_aggregate), taken on the decimal digits (measurements.h decimal_mean),
// so cell means equal as decimals are equal doubles and rank tests see their
// ties, as on R's aggregate(); a cell with no row, or with a missing value among its rows,
// is missing, and a subject with any missing cell is removed (listwise
// deletion) with a warning that names the subject and the cell. A between-
// subject factor that changes within a subject is an Error naming both lines.
// Runs in O(rows) with hash lookups (10^6 rows in well under a second).
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/long_data.h"
#include "study/common/error.h"

namespace dtlab::stats::detail {

struct CellDesign {
  std::vector<std::string> subjects;                    // kept subjects, first-appearance order
  std::vector<std::string> within_names;                // within factors
  std::vector<std::vector<std::string>> within_levels;  // their levels
  std::vector<std::string> between_names;
  std::vector<std::vector<std::string>> between_levels;
  std::vector<std::vector<size_t>> group;               // group[s][f]: level of between factor f for subject s
  size_t cells = 1;                                     // product of the within levels; cell index has the last factor fastest
  std::vector<std::vector<double>> delta;               // delta[s][c]: cell value minus the dv offset (exact offset removed)
  std::vector<std::vector<double>> value;               // value[s][c]: cell value (as R holds it)
  std::vector<std::vector<double>> noise;               // noise[s][c]: bound on the rounding error of delta[s][c]
  std::vector<std::vector<Decimal>> decimal;            // decimal[s][c]: the cell value as a decimal (empty for data
                                                        // given as doubles); aggregated cells hold their exact mean
  Measurements dv_scale;                                // the dv's offset and offset_decimal (no rows), for describe()
  double offset = 0.0;                                  // dv offset (value = offset + delta)
  std::vector<std::string> dropped;                     // subjects removed by listwise deletion
  std::vector<std::string> warnings;

  std::vector<size_t> cell_levels(size_t cell) const;   // level index per within factor
  std::string cell_label(size_t cell) const;            // "angle=0, noise=absent"
  std::string cell_name(size_t cell) const;             // "0:absent" (the levels alone)
};

// Requires data.subject to be filled (one id per row).
Result<CellDesign> build_cell_design(const LongData& data);

// Subject s's mean over `cells` (indices into its cells): {value, delta}.
// Taken on the decimal digits when the data came as text, so means equal as
// decimals are equal doubles (ties stay ties for rank tests and zero
// differences stay zero); else a compensated sum over the count.
struct CellMean {
  double value = 0, delta = 0;
};
CellMean subject_mean(const CellDesign& d, size_t s, const std::vector<size_t>& cells);

// Each subject's mean over the other within factors at every level of within
// factor f, [level][subject]: of the values (as R holds them, for rank tests)
// and of the deltas (for t tests; the offset cancels in differences).
struct FactorMarginals {
  std::vector<std::vector<double>> value, delta;
};
FactorMarginals factor_marginals(const CellDesign& d, size_t f);

// "a, b, c and 7 more": at most `shown` names of a list, each through name_for_message().
std::string name_list(const std::vector<std::string>& names, size_t shown = 10);

}  // namespace dtlab::stats::detail
