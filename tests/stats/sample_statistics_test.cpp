// Quantiles and medians against answers worked out on paper.
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

TEST(Median, IsTheMiddleValueOrTheMeanOfTheTwoMiddleOnes) {
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({-1.0}), -1.0);
  EXPECT_TRUE(std::isnan(median({})));
  // The same as the interpolated 0.5-quantile.
  const std::vector<double> v = {0.3, 9.1, -2.0, 4.4, 4.4, 7.0};
  EXPECT_DOUBLE_EQ(median(v), quantile(v, 0.5));
}

}  // namespace
}  // namespace msislab
