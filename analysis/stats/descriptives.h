// Descriptive statistics of one sample: n, mean, SD (n - 1 denominator), SE,
// 95% confidence interval of the mean (mean +- t(0.975, n - 1) SE), median,
// quartiles and IQR with R's default quantile definition (type 7:
// x[h] interpolated at h = (n - 1) p). Missing values (NaN) are skipped.
// Values are taken relative to an offset so that data sharing many leading
// digits keep their precision (see measurements.h).
// Defined results: n = 0 gives NaN everywhere; n = 1 gives sd, se and the CI
// as NaN (R's sd() of one value is NA). Validated against R 4.x (mean, sd,
// quantile(type = 7), t.test()$conf.int) on the sleep data.
#pragma once
#include <cstddef>
#include <vector>

namespace dtlab::stats {

struct Descriptives {
  size_t n = 0;       // non-missing values
  double mean = 0, sd = 0, se = 0;
  double ci_low = 0, ci_high = 0;  // 95% CI of the mean
  double median = 0, q1 = 0, q3 = 0, iqr = 0;
  double min = 0, max = 0;
};

// Of offset + d for each d in deltas (NaN = missing).
Descriptives describe(const std::vector<double>& deltas, double offset = 0.0);

}  // namespace dtlab::stats
