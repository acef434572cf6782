// Quantiles, medians and the two-sample KS distance against answers worked out on paper.
#include "stats/sample_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace msislab {
namespace {

TEST(Quantile, InterpolatesBetweenOrderStatistics) {
  const std::vector<double> v = {5.0, 1.0, 4.0, 2.0, 3.0};  // unsorted on purpose
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.1), 1.4);  // h = 0.4
  EXPECT_DOUBLE_EQ(quantile(v, 0.9), 4.6);  // h = 3.6
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 5.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.5), 5.0);  // p clamped
  EXPECT_DOUBLE_EQ(quantile({7.0}, 0.9), 7.0);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(Mean, IsTheSumOverTheCount) {
  EXPECT_DOUBLE_EQ(mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_TRUE(std::isnan(mean({})));
}

TEST(Rms, IsTheSpreadAboutZero) {
  EXPECT_NEAR(rms({3.0, -4.0}), std::sqrt(12.5), 1e-12);
  EXPECT_NEAR(rms({-2.0, -2.0, -2.0}), 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(rms({})));
}

TEST(Median, IsTheMiddleValueOrTheMeanOfTheTwoMiddleOnes) {
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({-1.0}), -1.0);
  EXPECT_TRUE(std::isnan(median({})));
  // The same as the interpolated 0.5-quantile.
  const std::vector<double> v = {0.3, 9.1, -2.0, 4.4, 4.4, 7.0};
  EXPECT_DOUBLE_EQ(median(v), quantile(v, 0.5));
}

TEST(KsDistance, IdenticalSamplesAreZeroApart) {
  const std::vector<double> a = {3.0, 1.0, 2.0, 2.0, 8.5};
  EXPECT_DOUBLE_EQ(ks_distance(a, a), 0.0);
  // The same distribution at another sample size: every step of F is the same.
  EXPECT_DOUBLE_EQ(ks_distance({1.0, 2.0}, {1.0, 1.0, 2.0, 2.0}), 0.0);
}

TEST(KsDistance, DisjointSamplesAreOneApart) {
  EXPECT_DOUBLE_EQ(ks_distance({1.0, 2.0, 3.0}, {3.5, 10.0}), 1.0);
  EXPECT_DOUBLE_EQ(ks_distance({3.5, 10.0}, {1.0, 2.0, 3.0}), 1.0);
}

TEST(KsDistance, KnownShift) {
  // 0..99 against 10..109: F_a - F_b = 10/100 on [10, 100).
  std::vector<double> a, b;
  for (int i = 0; i < 100; ++i) {
    a.push_back(i);
    b.push_back(i + 10);
  }
  EXPECT_NEAR(ks_distance(a, b), 0.1, 1e-12);
  // Ties count at once: F_a(1) = 2/3, F_b(1) = 1/3.
  EXPECT_NEAR(ks_distance({1.0, 1.0, 2.0}, {1.0, 2.0, 2.0}), 1.0 / 3.0, 1e-12);
  EXPECT_TRUE(std::isnan(ks_distance({}, {1.0})));
}

}  // namespace
}  // namespace msislab
