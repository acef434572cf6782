// Calibration states of trajectory SLAM (docs/trajectory_slam.md, "Calibration states"): the
// sonar's range scale, estimated with the trajectory. Its observation Jacobian against finite
// differences in both filters, during and after a robocentric step; its recovery on the synthetic
// loop whose scans see the basin 4 % small (within two standard deviations, the trajectory then
// better than without the state); and the filters unchanged, to the byte, with it switched off.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "slam/robocentric_slam.hpp"
#include "slam/worldcentric_slam.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

/// Exposes a filter's state for finite differences.
template <class Filter>
class Open : public Filter {
 public:
  using Filter::Filter;
  using Filter::predict;
  std::vector<Pose2>& state() { return this->elements_; }
  Eigen::VectorXd& parameters() { return this->calibration_; }
};

TrajectorySlamConfig with_range_scale() {
  TrajectorySlamConfig config;
  config.calibration.range_scale = true;
  return config;
}

/// The loop's scans seeing the world s times its size (a sonar whose ranges are s times true).
Loop scaled(Loop loop, double s) {
  for (Scan& scan : loop.scans) {
    for (ScanPoint& p : scan.points) {
      p.p_m *= s;
      p.p_vehicle_m *= s;
      p.cov *= s * s;
      p.cov_reading *= s * s;
    }
  }
  return loop;
}

/// Checks H of observed_relative_pose(a, b) against central differences over the range scale
/// (column 0) and the elements a+1..b (the next 3(b-a) columns).
template <class Filter>
void expect_observation_jacobian(Filter& slam, std::size_t a, std::size_t b) {
  Eigen::MatrixXd H;
  slam.observed_relative_pose(a, b, &H);
  ASSERT_EQ(H.cols(), static_cast<Eigen::Index>(1 + 3 * (b - a)));
  const double step = 1e-6;
  const auto numeric = [&](auto perturb) {
    perturb(step);
    const Pose2 plus = slam.observed_relative_pose(a, b, nullptr);
    perturb(-2 * step);
    const Pose2 minus = slam.observed_relative_pose(a, b, nullptr);
    perturb(step);
    return Eigen::Vector3d(pose_difference(plus, minus) / (2 * step));
  };
  EXPECT_LT((H.col(0) - numeric([&](double d) { slam.parameters()(0) += d; })).norm(), 1e-6)
      << "a " << a << " b " << b << " range scale";
  for (Eigen::Index c = 1; c < H.cols(); ++c) {
    const std::size_t element = a + 1 + static_cast<std::size_t>((c - 1) / 3);
    const auto perturb = [&](double d) {
      Eigen::Vector3d v = slam.state()[element].vector();
      v((c - 1) % 3) += d;
      slam.state()[element] = Pose2(v);
    };
    EXPECT_LT((H.col(c) - numeric(perturb)).norm(), 1e-6)
        << "a " << a << " b " << b << " column " << c;
  }
}

TEST(CalibrationStates, RangeScaleObservationJacobians) {
  const Loop loop = scaled(make_loop(2, false), 0.96);
  Open<WorldCentricSlam> world(with_range_scale(), GaussianPose2{});
  Open<RoboCentricSlam> robot(with_range_scale(), GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  ASSERT_NE(world.parameters()(0), 1.0);  // the matches have moved it
  expect_observation_jacobian(world, 1, 5);
  expect_observation_jacobian(world, 6, 7);
  expect_observation_jacobian(robot, 0, 7);
  expect_observation_jacobian(robot, 2, 4);
  robot.predict(loop.scans[8].motion);  // the raw newest element, as during a step
  expect_observation_jacobian(robot, 1, 8);
  expect_observation_jacobian(robot, 7, 8);
}

class BothFilters : public testing::TestWithParam<std::string> {};

std::unique_ptr<TrajectorySlam> make_filter(const std::string& method,
                                            const TrajectorySlamConfig& config) {
  if (method == "robocentric") return std::make_unique<RoboCentricSlam>(config, GaussianPose2{});
  return std::make_unique<WorldCentricSlam>(config, GaussianPose2{});
}

double mean_error_m(const TrajectorySlam& slam, const std::vector<Pose2>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < slam.scans(); ++i) {
    sum += (slam.scan_pose_world(i).mean.translation() - truth[i].translation()).norm();
  }
  return sum / static_cast<double>(slam.scans());
}

TEST_P(BothFilters, RecoverTheRangeScaleOfScansThatSeeTheWorld4PercentSmall) {
  // Ten loops (seeds 1-10): the estimate within two of its standard deviations of 0.96 in at
  // least 9, and the mean error below the filter's without the state in at least 9.
  int within = 0, better = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Loop loop = scaled(make_loop(seed, false), 0.96);
    const auto estimating = make_filter(GetParam(), with_range_scale());
    const auto ignoring = make_filter(GetParam(), TrajectorySlamConfig{});
    for (const Scan& scan : loop.scans) estimating->add_scan(scan), ignoring->add_scan(scan);
    const std::vector<CalibrationEstimate> c = estimating->calibration();
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].name, "range_scale");
    EXPECT_LT(c[0].sigma, 0.02) << "seed " << seed << ": the matches inform it";
    within += std::abs(c[0].value - 0.96) < 2.0 * c[0].sigma;
    const double with_m = mean_error_m(*estimating, loop.truth);
    const double without_m = mean_error_m(*ignoring, loop.truth);
    better += with_m < without_m;
    std::cout << GetParam() << " seed " << seed << ": range scale " << c[0].value << " +- "
              << c[0].sigma << ", mean error " << with_m << " m (without the state " << without_m
              << " m)\n";
  }
  EXPECT_GE(within, 9);
  EXPECT_GE(better, 9);
}

TEST_P(BothFilters, SwitchedOffTheStateLeavesNoParameterAndNoEstimate) {
  const auto slam = make_filter(GetParam(), TrajectorySlamConfig{});
  const Loop loop = make_loop(3, false);
  for (const Scan& scan : loop.scans) slam->add_scan(scan);
  EXPECT_TRUE(slam->calibration().empty());
  EXPECT_EQ(slam->calibration_parameters().size(), 0);
  EXPECT_EQ(slam->covariance().rows(), static_cast<Eigen::Index>(3 * slam->scans()));
}

INSTANTIATE_TEST_SUITE_P(CalibrationStates, BothFilters,
                         testing::Values("robocentric", "worldcentric"));

}  // namespace
}  // namespace msislab
