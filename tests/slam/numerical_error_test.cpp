// Numerical hygiene: a state or covariance that becomes non-finite (here: motions whose finite but
// enormous covariances overflow once chained) stops every back end with a NumericalError naming
// the scan, in the step's stage or in the read-out of a pose, instead of NaN poses written as if
// valid.
#include "slam/numerical_error.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "slam/dead_reckoning.hpp"
#include "slam/pose_graph_slam.hpp"
#include "slam/robocentric_slam.hpp"
#include "slam/worldcentric_slam.hpp"

namespace msislab {
namespace {

/// A scan with no points (matching skipped) and a compass reading, after a motion of 1 m whose
/// covariance is finite but so large that two of them chained overflow.
Scan overflowing_scan(int k) {
  Scan scan;
  scan.t_s = 10.0 * k;
  scan.motion.mean = Pose2(1.0, 0.0, 0.0);
  scan.motion.cov = 1e308 * Eigen::Matrix3d::Identity();
  scan.compass_yaw_world_rad = 0.0;
  scan.compass_sigma_rad = 0.01;
  return scan;
}

/// Adding the scans and reading every pose back: a NumericalError naming the estimator and the
/// scan, in the step or in the read-out, never a non-finite pose.
void expect_numerical_error(ScanSlam& slam, const std::string& who) {
  try {
    for (int k = 0; k < 10; ++k) {
      slam.add_scan(overflowing_scan(k));
      slam.finish();
      for (std::size_t i = 0; i < slam.scans(); ++i) slam.scan_pose_world(i);
    }
    ADD_FAILURE() << who << ": no NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(who + ": scan ", 0), 0u) << what;
    EXPECT_NE(what.find("is not finite"), std::string::npos) << what;
  }
}

TEST(NumericalError, FiltersStopWhereTheStateBecomesNonFinite) {
  const TrajectorySlamConfig config;
  RoboCentricSlam robocentric(config, GaussianPose2{});
  expect_numerical_error(robocentric, "trajectory SLAM");
  WorldCentricSlam worldcentric(config, GaussianPose2{});
  expect_numerical_error(worldcentric, "trajectory SLAM");
}

TEST(NumericalError, PoseGraphStopsWhereItsBeliefBecomesNonFinite) {
  PoseGraphSlam graph(ScanFrontEndConfig{}, CalibrationStatesConfig{}, PoseGraphSlamConfig{},
                      GaussianPose2{});
  expect_numerical_error(graph, "pose graph");
}

TEST(NumericalError, DeadReckoningStopsWhereItsPoseBecomesNonFinite) {
  NavigationLog log;
  for (int k = 1; k <= 20; ++k) {
    // Finite readings whose integration overflows: 1e307 m/s for seconds.
    log.dvl.push_back({1.0 * k, Eigen::Vector2d(1e307, 1e307)});
    log.heading.push_back({1.0 * k + 0.5, 0.0});
  }
  DeadReckoningConfig config;
  config.dvl_gate_chi2 = 0.0;  // no gate: every reading is used
  try {
    run_dead_reckoning(log, config, Eigen::Vector2d::Zero(), StampedPose{});
    ADD_FAILURE() << "no NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("dead reckoning: pose ", 0), 0u) << e.what();
  }
}

TEST(NumericalError, FiniteStatesPass) {
  EXPECT_NO_THROW(require_finite(true, "x", 0, 0.0, "prediction"));
  EXPECT_THROW(require_finite(false, "x", 3, 30.0, "prediction"), NumericalError);
}

}  // namespace
}  // namespace msislab
