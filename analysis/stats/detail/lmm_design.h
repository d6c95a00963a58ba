// The design matrices of a mixed model as lme4 builds them from an afex-style
// call: fixed effects are the full factorial of the named factors coded with
// contr.sum (level j < K: indicator of j; the last level: -1 in every
// column), terms in R's order (by degree, then by R's term bit order) with
// the first factor of an interaction varying fastest; random-effect terms
// are (grouping factor, columns of X), ordered as lme4's mkReTrms orders them.
// Guarantees: column names are R's ("(Intercept)", "A1", "A1:B2"); level
// order is R's factor() order (numeric labels by value, others bytewise).
// Never looks at the response; never fails on valid factor data.
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

namespace dtlab::stats::detail {

// One categorical variable with its levels in R's order and a level index per row.
struct CodedFactor {
  std::string name;
  std::vector<std::string> levels;
  std::vector<int> index;  // index[row] into levels
  bool within = true;      // within-subject (true) or between-subject (false)
};

// Builds a CodedFactor from row labels; levels sorted as R's factor() sorts
// them (all labels numbers: by value; otherwise bytewise, R's C locale).
CodedFactor code_factor(const std::string& name, const std::vector<std::string>& labels, bool within);

// contr.sum(K)[level, column]: 1 on the level's own column, -1 for the last level.
double contr_sum(int level, int column, int levels);

struct FixedTerm {
  std::string name;          // "A", "A:B"
  std::vector<int> factors;  // indices into FixedDesign::factors, in factor order
  std::vector<int> columns;  // columns of X that code it
};

struct FixedDesign {
  std::vector<CodedFactor> factors;
  std::vector<FixedTerm> terms;           // R's term.labels order (without the intercept)
  std::vector<std::string> column_names;  // "(Intercept)", then each term's columns
  Eigen::MatrixXd X;                      // rows x columns

  // The X row of one cell (a level index per factor).
  Eigen::RowVectorXd cell_row(const std::vector<int>& levels) const;
};

// The full factorial with contr.sum coding (afex's default).
FixedDesign fixed_design(std::vector<CodedFactor> factors);

// The type III hypothesis of a term as lmerTest forms it for contr.sum
// codings: one row per combination of non-first levels (first factor
// fastest), the interaction contrast of (level - first level) of each factor
// written in the sum-to-zero parameters; zero outside the term's columns.
Eigen::MatrixXd type3_hypothesis(const FixedDesign& design, const FixedTerm& term);

// A grouping factor of the random effects (subject, item).
struct Grouping {
  std::string name;
  std::vector<std::string> levels;
  std::vector<int> index;  // index[row]
};

// One random-effects term (columns | grouping): columns of X, 0 = intercept.
struct RandomTerm {
  int grouping = 0;
  std::vector<int> columns;
};

// lme4's term order: when some term has more levels than the term before it,
// terms are sorted by decreasing number of levels (rev(order(nl)), so ties
// end up reversed); otherwise the formula's order is kept.
std::vector<RandomTerm> lme4_term_order(std::vector<RandomTerm> terms, const std::vector<Grouping>& groupings);

}  // namespace dtlab::stats::detail
