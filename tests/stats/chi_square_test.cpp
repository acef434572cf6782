// The chi-square distribution against printed tables: quantiles (gates), the survival function
// as their inverse, and the bounds of an average used by the NEES tests.
#include "stats/chi_square.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace msislab {
namespace {

TEST(ChiSquare, QuantilesMatchTheTables) {
  EXPECT_NEAR(chi2_quantile(0.99, 1), 6.635, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.99, 2), 9.210, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.99, 3), 11.345, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.95, 3), 7.815, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.95, 1), 3.841, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.99, 6), 16.812, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.99, 9), 21.666, 1e-3);
  EXPECT_NEAR(chi2_quantile(0.95, 30), 43.773, 1e-3);
}

TEST(ChiSquare, SurvivalInvertsTheQuantile) {
  for (const double dof : {1.0, 2.0, 3.0, 7.0, 150.0}) {
    for (const double p : {0.025, 0.5, 0.99}) {
      EXPECT_NEAR(chi2_survival(chi2_quantile(p, dof), dof), 1.0 - p, 1e-12) << dof << " " << p;
    }
  }
  EXPECT_DOUBLE_EQ(chi2_survival(0.0, 3), 1.0);
}

TEST(ChiSquare, QuantileEndsAreZeroAndInfinity) {
  // A gate of 1e9 (no gate) has survival 0: the gate in other dimensions is then infinite too.
  EXPECT_EQ(chi2_survival(1e9, 3), 0.0);
  EXPECT_EQ(chi2_quantile(1.0 - chi2_survival(1e9, 3), 2), std::numeric_limits<double>::infinity());
  EXPECT_EQ(chi2_quantile(0.0, 2), 0.0);
}

TEST(ChiSquare, AverageBoundsMatchTheFieldNotes) {
  // ../shared/docs/field-notes.md: N=1 [0.216, 9.35], N=25 [2.12, 4.03], N=50 [2.36, 3.72],
  // N=100 [2.54, 3.50].
  const auto b1 = average_chi2_bounds(1, 3), b25 = average_chi2_bounds(25, 3),
             b50 = average_chi2_bounds(50, 3), b100 = average_chi2_bounds(100, 3);
  EXPECT_NEAR(b1.first, 0.216, 1e-3);
  EXPECT_NEAR(b1.second, 9.35, 0.01);
  EXPECT_NEAR(b25.first, 2.12, 0.01);
  EXPECT_NEAR(b25.second, 4.03, 0.01);
  EXPECT_NEAR(b50.first, 2.36, 0.01);
  EXPECT_NEAR(b50.second, 3.72, 0.01);
  EXPECT_NEAR(b100.first, 2.54, 0.01);
  EXPECT_NEAR(b100.second, 3.50, 0.01);
}

}  // namespace
}  // namespace msislab
