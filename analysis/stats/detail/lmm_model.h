// From LmmData to what a mixed-model fit needs: the rows kept (missing dv
// left out, as lme4's na.omit), the transformed response, the contr.sum
// fixed design, the grouping factors, which factors vary within each
// grouping factor, the random-effects structure a RandomEffects choice
// asks for (the largest the design identifies: lme4 stops when a term has
// as many random effects as rows), and the lme4 formula and R code text.
// Guarantees: an Error (file:line where it helps) for data no fit can use;
// the formula is one lme4 parses into the same model. Never fits anything.
#pragma once
#include <string>
#include <vector>

#include "analysis/stats/detail/lmm_design.h"
#include "analysis/stats/lmm.h"

namespace dtlab::stats::detail {

struct PreparedModel {
  FixedDesign design;
  Eigen::VectorXd y;                 // response after the transform (rows kept), minus y_offset
  double y_offset = 0;               // the dv's exact offset (measurements.h) for an untransformed gaussian dv
  std::vector<Grouping> groupings;   // [0] subject, [1] item when given
  std::vector<std::vector<bool>> varies;  // varies[g][f]: factor f changes within some level of grouping g
  std::string dv_expr;               // "time", "log(time)"
  std::size_t rows_read = 0;
  std::size_t missing = 0;           // rows left out for a missing dv
};

// Checks and codes the data (see fit_lmm's Errors).
Result<PreparedModel> prepare_model(const LmmData& data, const LmmOptions& options);

// A random-effects term as written in a formula: (1 + cols | g) or (1 + cols || g).
struct FormulaTerm {
  int grouping = 0;
  std::vector<int> columns;  // X columns, 0 = intercept (always first when present)
  bool correlated = true;
};

// The terms RandomEffects asks for, reduced until every term has fewer random
// effects than rows (lme4's check.nobs.vs.nRE); notes say what was reduced.
std::vector<FormulaTerm> random_structure(const PreparedModel& m, RandomEffects random,
                                          std::vector<std::string>& notes);

// lme4 terms of a formula structure, in lme4's order (|| split per column).
std::vector<RandomTerm> expand_terms(const std::vector<FormulaTerm>& terms, const std::vector<Grouping>& groupings);

// The formula: "log(time) ~ A * B + (1 + A + B + A:B | subject) + (1 | item)".
std::string lme4_formula(const PreparedModel& m, const std::vector<FormulaTerm>& terms);

// R lines that build the numeric contrast columns used by || terms, fit the
// same model with lmerTest / lme4 and print what dtlab prints.
std::string r_code(const PreparedModel& m, const std::vector<FormulaTerm>& terms, const LmmOptions& o);

// An R name: as is when syntactic, else in backticks.
std::string r_name(const std::string& name);

// The name of the numeric column for X column c in || terms ("re_A1_B1").
std::string re_column_name(const PreparedModel& m, int column);

}  // namespace dtlab::stats::detail
