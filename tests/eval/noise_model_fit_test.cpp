// The noise-model fits recover known parameters from long synthetic sequences drawn from the
// models themselves, within the stated tolerances (a few standard errors at these lengths).
#include "eval/noise_model_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include "test_support.hpp"
#include "tests/draws.hpp"

namespace msislab {
namespace {

std::vector<Eigen::Vector2d> contaminated_differences(double core, double fraction, double outlier,
                                                      int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::bernoulli_distribution is_outlier(fraction);
  std::vector<Eigen::Vector2d> e, d;
  for (int i = 0; i < n; ++i) {
    const double sigma = is_outlier(rng) ? outlier : core;
    e.push_back(sigma * draws_last_first<2>([&] { return n01(rng); }));
    if (i > 0) d.push_back(e[i] - e[i - 1]);
  }
  return d;
}

TEST(ContaminatedNormal, RecoversAHeavyTailedMixture) {
  // 40,000 samples; the St. Pere DVL fit is core 0.10, 25% at 0.37.
  const ContaminatedNormal fit =
      fit_contaminated_normal(contaminated_differences(0.1, 0.25, 0.37, 40000, testing::seed(1)));
  EXPECT_NEAR(fit.core_sigma, 0.1, 0.003);
  EXPECT_NEAR(fit.outlier_fraction, 0.25, 0.02);
  EXPECT_NEAR(fit.outlier_sigma, 0.37, 0.01);
}

TEST(ContaminatedNormal, RecoversRareOutliers) {
  const ContaminatedNormal fit =
      fit_contaminated_normal(contaminated_differences(0.2, 0.02, 1.0, 40000, testing::seed(2)));
  EXPECT_NEAR(fit.core_sigma, 0.2, 0.004);
  EXPECT_NEAR(fit.outlier_fraction, 0.02, 0.004);
  EXPECT_NEAR(fit.outlier_sigma, 1.0, 0.08);
}

TEST(ContaminatedNormal, GaussianNoiseKeepsItsVariance) {
  // Without outliers the split is arbitrary, but the total variance must be right.
  const ContaminatedNormal fit =
      fit_contaminated_normal(contaminated_differences(0.2, 0.0, 0.2, 40000, testing::seed(3)));
  const double total = std::sqrt((1.0 - fit.outlier_fraction) * std::pow(fit.core_sigma, 2) +
                                 fit.outlier_fraction * std::pow(fit.outlier_sigma, 2));
  EXPECT_NEAR(total, 0.2, 0.003);
  EXPECT_LE(fit.core_sigma, fit.outlier_sigma);
}

std::vector<bool> gilbert_elliott_sequence(const GilbertElliott& m, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double leave_degraded = 1.0 / m.degraded_mean_samples;
  const double enter_degraded = leave_degraded * m.degraded_fraction / (1.0 - m.degraded_fraction);
  bool degraded = u(rng) < m.degraded_fraction;
  std::vector<bool> lost;
  for (int i = 0; i < n; ++i) {
    lost.push_back(u(rng) < (degraded ? m.degraded_loss_probability : m.clear_loss_probability));
    degraded = degraded ? u(rng) >= leave_degraded : u(rng) < enter_degraded;
  }
  return lost;
}

TEST(GilbertElliott, RecoversBurstyLosses) {
  // Near the St. Pere fit, but 200,000 samples (40x the real log) for a tight check.
  GilbertElliott truth;
  truth.clear_loss_probability = 0.004;
  truth.degraded_loss_probability = 0.07;
  truth.degraded_fraction = 0.2;
  truth.degraded_mean_samples = 40.0;
  const GilbertElliott fit =
      fit_gilbert_elliott(gilbert_elliott_sequence(truth, 200000, testing::seed(4)));
  EXPECT_NEAR(fit.clear_loss_probability, 0.004, 0.0015);
  EXPECT_NEAR(fit.degraded_loss_probability, 0.07, 0.01);
  EXPECT_NEAR(fit.degraded_fraction, 0.2, 0.04);
  EXPECT_NEAR(fit.degraded_mean_samples, 40.0, 10.0);
}

TEST(GilbertElliott, RecoversStrongBursts) {
  GilbertElliott truth;
  truth.clear_loss_probability = 0.0;
  truth.degraded_loss_probability = 0.5;
  truth.degraded_fraction = 0.1;
  truth.degraded_mean_samples = 10.0;
  const GilbertElliott fit =
      fit_gilbert_elliott(gilbert_elliott_sequence(truth, 100000, testing::seed(5)));
  EXPECT_LT(fit.clear_loss_probability, 0.002);
  EXPECT_NEAR(fit.degraded_loss_probability, 0.5, 0.03);
  EXPECT_NEAR(fit.degraded_fraction, 0.1, 0.01);
  EXPECT_NEAR(fit.degraded_mean_samples, 10.0, 1.0);
}

}  // namespace
}  // namespace msislab
