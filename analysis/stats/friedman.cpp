// Friedman test; see friedman.h.
#include "analysis/stats/friedman.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/stats/detail/design.h"
#include "analysis/stats/detail/friedman_exact.h"
#include "analysis/stats/detail/numbers.h"
#include "analysis/stats/detail/ranks.h"
#include "analysis/stats/distributions.h"

namespace dtlab::stats {
namespace {

// State updates of the exact DP (friedman_exact_work, an upper bound): 3e8
// take at most about a second of CPU on the development machine (k = 6,
// n = 9: 0.5 s), 3e9 about seven (k = 6, n = 14: 5.1 s; k = 4, n = 160: 7.2 s).
constexpr double kFriedmanBudget = 3e8;   // --exact auto
constexpr double kAlwaysBudget = 3e9;  // --exact always

void set_undefined(FriedmanResult& r) {
  r.Q = r.p = r.log10_p = r.p_exact = r.kendall_W = kNaN;
  r.iman_davenport_F = r.p_iman_davenport = r.log10_p_iman_davenport = kNaN;
}

// p_exact by the exact permutation distribution or by Monte Carlo, as `exact` asks.
void permutation_p(FriedmanResult& r, const std::vector<std::vector<int>>& doubled, const ExactOptions& exact) {
  const std::int64_t s_obs = detail::friedman_s(doubled);
  r.p_exact = kNaN;
  auto run_monte_carlo = [&](std::size_t samples) {
    r.p_exact = detail::friedman_monte_carlo_tail(doubled, s_obs, samples, exact.seed, exact.progress);
    r.exact_method = "monte-carlo";
    r.monte_carlo_samples = samples;
    r.seed = exact.seed;
  };
  switch (exact.mode) {
    case ExactMode::never:
      break;
    case ExactMode::monte_carlo:
      run_monte_carlo(exact.monte_carlo_samples);
      break;
    case ExactMode::automatic:
    case ExactMode::always: {
      const bool always = exact.mode == ExactMode::always;
      std::string why;
      if (auto p = detail::friedman_exact_tail(doubled, s_obs, always ? kAlwaysBudget : kFriedmanBudget, &why)) {
        r.p_exact = *p;
        r.exact_method = "exact";
      } else {
        r.exact_note = "not enumerated: " + why + (always ? "" : " (--exact auto; always allows 10 times the work)") +
                       "; the chi-square p applies, --exact monte-carlo=N estimates the permutation p";
        if (always) r.warnings.push_back("p_exact " + r.exact_note);
      }
      break;
    }
  }
}

}  // namespace

FriedmanResult friedman_blocks(const std::vector<std::vector<double>>& y, const ExactOptions& exact) {
  FriedmanResult r;
  r.n = y.size();
  r.k = y.empty() ? 0 : y.front().size();
  for (const auto& row : y)
    if (row.size() != r.k) throw std::invalid_argument("friedman: every block needs the same number of treatments");
  const double n = static_cast<double>(r.n), k = static_cast<double>(r.k);
  r.df = k - 1.0;
  r.id_df1 = k - 1.0;
  r.id_df2 = (k - 1.0) * (n - 1.0);
  if (r.n == 0 || r.k < 2) {
    set_undefined(r);
    r.mean_ranks.assign(r.k, r.n == 0 ? kNaN : 1.0);
    r.warnings.push_back(r.n == 0 ? "no complete block: nothing to test" : "one treatment: nothing to compare");
    return r;
  }

  std::vector<double> rank_sum(r.k, 0.0);
  std::vector<std::vector<int>> doubled(r.n, std::vector<int>(r.k));
  double ties = 0.0;
  for (std::size_t i = 0; i < r.n; ++i) {
    const auto rk = detail::average_ranks(y[i]);
    for (std::size_t j = 0; j < r.k; ++j) {
      rank_sum[j] += rk[j];
      doubled[i][j] = static_cast<int>(std::lround(2.0 * rk[j]));
    }
    ties += detail::tie_sum(y[i]);
  }
  r.ties = ties > 0;
  for (double s : rank_sum) r.mean_ranks.push_back(s / n);

  double num = 0.0;
  for (double s : rank_sum) num += (s - n * (k + 1.0) / 2.0) * (s - n * (k + 1.0) / 2.0);
  const double denom = n * k * (k + 1.0) - ties / (k - 1.0);
  if (denom <= 0) {  // every block fully tied: 0/0
    set_undefined(r);
    r.warnings.push_back("every block is fully tied: the Friedman statistic is 0/0 (undefined), as in R");
    return r;
  }
  r.Q = 12.0 * num / denom;
  const Tail chi = chi_squared_upper(r.Q, r.df);
  r.p = chi.p;
  r.log10_p = chi.log10_p;
  r.kendall_W = r.Q / (n * (k - 1.0));

  if (r.n < 2) {
    r.iman_davenport_F = r.p_iman_davenport = r.log10_p_iman_davenport = kNaN;
    r.warnings.push_back("one block: the Iman-Davenport F has no error degrees of freedom");
  } else {
    const double spare = n * (k - 1.0) - r.Q;
    r.iman_davenport_F = spare > 1e-12 * n * (k - 1.0) ? (n - 1.0) * r.Q / spare : std::numeric_limits<double>::infinity();
    if (std::isinf(r.iman_davenport_F))
      r.warnings.push_back("perfect agreement (Kendall's W = 1): every block ranks the treatments alike, so the "
                           "Iman-Davenport F is infinite and its p is 0");
    const Tail f = f_upper(r.iman_davenport_F, r.id_df1, r.id_df2);
    r.p_iman_davenport = f.p;
    r.log10_p_iman_davenport = f.log10_p;
  }

  permutation_p(r, doubled, exact);
  return r;
}

Result<FriedmanResult> friedman(const LongData& data, const ExactOptions& exact) {
  if (!data.between.empty())
    return Error{data.source, 0, 0, data.between.front().name, "the Friedman test takes no between-subject factor"};
  if (data.within.empty()) return Error{data.source, 0, 0, "", "the Friedman test needs a within-subject factor"};
  auto built = detail::build_cell_design(data);
  if (!built) return built.error();
  const detail::CellDesign& d = *built;
  if (d.cells < 2)
    return Error{data.source, 0, 0, data.within.front().name,
                 "the Friedman test needs at least two treatments (cells); this design has " + std::to_string(d.cells)};
  if (d.subjects.empty())
    return Error{data.source, 0, 0, "", "no subject has every cell: nothing left after listwise deletion"};
  FriedmanResult r = friedman_blocks(d.value, exact);
  for (std::size_t c = 0; c < d.cells; ++c) r.treatments.push_back(d.cell_name(c));
  r.dropped_blocks = d.dropped;
  r.warnings.insert(r.warnings.begin(), d.warnings.begin(), d.warnings.end());
  return r;
}

}  // namespace dtlab::stats
