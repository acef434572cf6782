// The filters' state opened for finite differences, and the check of a match's observation
// Jacobian against them. Shared by the calibration-state and scan-registration-error tests.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "geometry/se2.hpp"

namespace msislab {

/// Exposes a filter's state for finite differences.
template <class Filter>
class Open : public Filter {
 public:
  using Filter::compass_residual;
  using Filter::Filter;
  using Filter::predict;
  using Filter::stacked_residual;
  std::vector<Pose2>& state() { return this->elements_; }
  Eigen::VectorXd& parameters() { return this->calibration_; }
  Eigen::Vector2d& deviation_change() { return this->deviation_change_; }
  std::vector<Eigen::Vector3d>& velocities() { return this->velocities_; }
};

/// Checks H of observed_relative_pose(a, b) against central differences over the calibration
/// parameters (the first c columns) and the elements a+1..b (the next 3(b-a) columns).
template <class Filter>
void expect_observation_jacobian(Filter& slam, std::size_t a, std::size_t b) {
  Eigen::MatrixXd H;
  slam.observed_relative_pose(a, b, &H);
  const Eigen::Index c = slam.parameters().size();
  ASSERT_EQ(H.cols(), static_cast<Eigen::Index>(c + 3 * (b - a)));
  const double step = 1e-6;
  const auto numeric = [&](auto perturb) {
    perturb(step);
    const Pose2 plus = slam.observed_relative_pose(a, b, nullptr);
    perturb(-2 * step);
    const Pose2 minus = slam.observed_relative_pose(a, b, nullptr);
    perturb(step);
    return Eigen::Vector3d(pose_difference(plus, minus) / (2 * step));
  };
  for (Eigen::Index i = 0; i < c; ++i) {
    EXPECT_LT((H.col(i) - numeric([&](double d) { slam.parameters()(i) += d; })).norm(), 1e-6)
        << "a " << a << " b " << b << " parameter " << i;
  }
  for (Eigen::Index col = c; col < H.cols(); ++col) {
    const std::size_t element = a + 1 + static_cast<std::size_t>((col - c) / 3);
    const auto perturb = [&](double d) {
      Eigen::Vector3d v = slam.state()[element].vector();
      v((col - c) % 3) += d;
      slam.state()[element] = Pose2(v);
    };
    EXPECT_LT((H.col(col) - numeric(perturb)).norm(), 1e-6)
        << "a " << a << " b " << b << " column " << col;
  }
}

}  // namespace msislab
