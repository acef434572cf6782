// A fixture for tools/check_stat_bounds.sh (tests/CMakeLists.txt): one bound that names no
// statistic and one that does, both in tests that draw. Not compiled.
#include <gtest/gtest.h>

#include <random>

TEST(Fixture, Bare) {
  std::mt19937 rng(testing::seed(1));
  const double x = std::normal_distribution<double>(0.0, 0.1)(rng);
  EXPECT_LT(x, 0.3);
}

TEST(Fixture, Named) {
  std::mt19937 rng(testing::seed(2));
  const double x = std::normal_distribution<double>(0.0, 0.1)(rng);
  EXPECT_LT(x, 0.33);  // N(0, 0.1^2): false alarm 0.001
}
