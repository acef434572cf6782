// Chain composition: the result equals step-by-step composition, and every analytic Jacobian
// matches central finite differences, for chains of 1 to 12 motions with yaws across the wrap.
#include "geometry/pose_chain.hpp"

#include <gtest/gtest.h>

#include <random>

namespace msislab {
namespace {

TEST(PoseChain, EmptyChainIsTheIdentity) {
  std::vector<Eigen::Matrix3d> J;
  EXPECT_EQ(compose_chain({}, &J).vector(), Eigen::Vector3d::Zero());
  EXPECT_TRUE(J.empty());
}

TEST(PoseChain, JacobiansMatchFiniteDifferences) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xy(-5.0, 5.0), yaw(-M_PI, M_PI);
  const double h = 1e-6;
  for (int trial = 0; trial < 60; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(trial % 12);
    std::vector<Pose2> chain;
    for (std::size_t j = 0; j < n; ++j) {
      const double yaw_rad = yaw(rng), y_m = xy(rng), x_m = xy(rng);  // tests/draws.hpp's order
      chain.emplace_back(x_m, y_m, yaw_rad);
    }
    if (trial % 5 == 0) chain[0] = Pose2(1.0, 2.0, M_PI - 1e-9);  // at the wrap
    std::vector<Eigen::Matrix3d> J;
    const Pose2 T = compose_chain(chain, &J);
    Pose2 stepwise;
    for (const Pose2& x : chain) stepwise = stepwise.compose(x);
    EXPECT_LT(pose_difference(T, stepwise).norm(), 1e-12);
    ASSERT_EQ(J.size(), n);
    for (std::size_t j = 0; j < n; ++j) {
      Eigen::Matrix3d numeric;
      for (int k = 0; k < 3; ++k) {
        std::vector<Pose2> plus = chain, minus = chain;
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d(k) = h;
        plus[j] = Pose2(chain[j].vector() + d);
        minus[j] = Pose2(chain[j].vector() - d);
        numeric.col(k) = pose_difference(compose_chain(plus), compose_chain(minus)) / (2.0 * h);
      }
      // Tolerance: central differences with h = 1e-6 on poses of O(10 m): 1e-6 relative.
      EXPECT_LT((J[j] - numeric).norm(), 1e-6 * std::max(1.0, numeric.norm()))
          << "trial " << trial << ", element " << j << "\n"
          << J[j] << "\nvs\n"
          << numeric;
    }
  }
}

}  // namespace
}  // namespace msislab
