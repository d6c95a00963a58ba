// Holm's correction, pairwise post-hoc comparisons and descriptives.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/stats/descriptives.h"
#include "analysis/stats/paired.h"
#include "analysis/stats/posthoc.h"
#include "test_util.h"

namespace dtlab::stats {
namespace {

using test::near_rel;
using test::printed;

struct HolmCase {
  std::vector<double> p, adjusted;
};

TEST(Holm, StepDownAsPAdjust) {
  // Holm (1979). Expected: R 4.2.2 p.adjust(p, "holm") for each p below:
  //   c(0.01, 0.02, 0.03, 0.04, 0.05) -> 0.05 0.08 0.09 0.09 0.09;  c(0.04, 0.01, 0.03) -> 0.06 0.03 0.06
  //   c(0.5, 0.6) -> 1 1;  c(0.02, NA, 0.01) -> 0.02 NA 0.02
  const double nan = std::nan("");
  const std::vector<HolmCase> cases{
      {{0.01, 0.02, 0.03, 0.04, 0.05}, {0.05, 0.08, 0.09, 0.09, 0.09}},
      {{0.04, 0.01, 0.03}, {0.06, 0.03, 0.06}},
      {{0.5, 0.6}, {1.0, 1.0}},
      {{0.02, nan, 0.01}, {0.02, nan, 0.02}},  // NaN kept and not counted in m
      {{}, {}},
  };
  for (const auto& c : cases) {
    const auto a = holm(c.p);
    ASSERT_EQ(a.size(), c.adjusted.size());
    for (size_t i = 0; i < a.size(); ++i) {
      if (std::isnan(c.adjusted[i])) {
        EXPECT_TRUE(std::isnan(a[i]));
      } else {
        EXPECT_NEAR(a[i], c.adjusted[i], 1e-15) << i;
      }
    }
  }
}

TEST(Posthoc, PairwisePairedTEqualsTheSingleTTests) {
  // Three conditions; each comparison is R's t.test(xi, xj, paired = TRUE) (sleep values for a, b).
  std::string csv = "id,cond,y\n";
  const double a[] = {0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
  const double b[] = {1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};
  const double c[] = {1.0, 0.5, 0.2, 0.3, 0.9, 3.0, 4.1, 1.2, 2.2, 2.5};
  for (int i = 0; i < 10; ++i)
    csv += std::to_string(i) + ",a," + std::to_string(a[i]) + "\n" + std::to_string(i) + ",b," + std::to_string(b[i]) +
           "\n" + std::to_string(i) + ",c," + std::to_string(c[i]) + "\n";
  const LongData d = test::long_from_text(csv, {"y", "id", {"cond"}, {}});
  auto r = pairwise_within(d, "cond", PairwiseTest::paired_t);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->size(), 3u);
  EXPECT_EQ((*r)[0].a, "a");
  EXPECT_EQ((*r)[0].b, "b");
  // R: t.test(extra ~ group, data = sleep, paired = TRUE): t = -4.0621, df = 9, p-value = 0.002833
  EXPECT_TRUE(printed((*r)[0].statistic, "-4.0621"));
  EXPECT_TRUE(printed((*r)[0].p, "0.002833"));
  // R 4.2.2: pairwise.t.test(y, g, paired = TRUE, p.adjust.method = "holm")$p.value
  //   b-a 0.00849867059215281, c-a 0.02369870191360855, c-b 0.0342018954536123
  EXPECT_NEAR((*r)[0].p_holm, 0.00849867059215281, 1e-12);
  EXPECT_NEAR((*r)[1].p_holm, 0.02369870191360855, 1e-12);
  EXPECT_NEAR((*r)[2].p_holm, 0.0342018954536123, 1e-12);
  // R 4.2.2: pairwise.wilcox.test(y, g, paired = TRUE, p.adjust.method = "none")$p.value
  //   b-a 0.00909069801592506, c-a 0.01653449266792267, c-b 0.0524794995592466
  //   (zeros/ties -> normal approximation with continuity correction, as wilcox.test)
  auto w = pairwise_within(d, "cond", PairwiseTest::wilcoxon);
  ASSERT_TRUE(w.ok());
  EXPECT_EQ((*w)[0].test, "wilcoxon");
  EXPECT_TRUE(near_rel((*w)[0].p, 0.00909069801592506, 1e-10));
  EXPECT_TRUE(near_rel((*w)[1].p, 0.01653449266792267, 1e-10));
  EXPECT_TRUE(near_rel((*w)[2].p, 0.0524794995592466, 1e-10));
  EXPECT_FALSE(pairwise_within(d, "nope", PairwiseTest::paired_t).ok());
}

TEST(Descriptives, SleepGroupOne) {
  // R: x <- sleep$extra[1:10]; mean(x) = 0.75; sd(x) = 1.78901; median(x) = 0.35;
  //    quantile(x) (type 7) 25% = -0.175, 75% = 1.700; IQR(x) = 1.875
  // R: t.test(x)$conf.int = -0.5297804 2.0297804
  const Descriptives d = describe({0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0});
  EXPECT_EQ(d.n, 10u);
  EXPECT_NEAR(d.mean, 0.75, 1e-15);
  EXPECT_TRUE(printed(d.sd, "1.78901"));
  EXPECT_NEAR(d.median, 0.35, 1e-15);
  EXPECT_NEAR(d.q1, -0.175, 1e-15);
  EXPECT_NEAR(d.q3, 1.7, 1e-15);
  EXPECT_NEAR(d.iqr, 1.875, 1e-15);
  EXPECT_TRUE(printed(d.ci_low, "-0.5297804"));
  EXPECT_TRUE(printed(d.ci_high, "2.0297804"));
  EXPECT_NEAR(d.se, d.sd / std::sqrt(10.0), 1e-15);
}

TEST(Descriptives, OffsetKeepsPrecisionAndDegenerateSizes) {
  // 1e12 + {0.1, 0.2, 0.3} given as offset + deltas: sd exactly 0.1 to double precision.
  const Descriptives d = describe({0.1, 0.2, 0.3}, 1e12);
  EXPECT_NEAR(d.sd, 0.1, 1e-15);
  EXPECT_EQ(d.mean, 1e12 + 0.2);
  const Descriptives one = describe({5.0});
  EXPECT_EQ(one.mean, 5.0);
  EXPECT_TRUE(std::isnan(one.sd));
  EXPECT_TRUE(std::isnan(one.ci_low));
  const Descriptives none = describe({std::nan("")});
  EXPECT_EQ(none.n, 0u);
  EXPECT_TRUE(std::isnan(none.mean));
}

}  // namespace
}  // namespace dtlab::stats
