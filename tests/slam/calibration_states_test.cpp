// Calibration states of trajectory SLAM (docs/trajectory_slam.md, "Calibration states"): the
// sonar's range scale, the DVL's scale factor, the sonar clock's offset, the compass deviation and
// the compass's walking heading bias, estimated with the trajectory. The observation Jacobians (a
// match's h with one parameter and with two, the compass residual's) against finite differences in
// both filters, during and after a robocentric step; the prediction's dependence on the DVL scale
// and the deviation against finite differences; recovery on the synthetic loop whose scans see the
// basin 4 % small, whose motions are 3 % long, whose scans are seen 0.1 s late, or whose compass
// deviates (the estimates consistent by their mean squared normalised error over ten loops, the
// world-centric filter giving the same estimates, the trajectory then better than without the
// state), or whose compass's bias walks (the yaw consistent with the state); and no parameter in
// the state with them switched off.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <string>

#include "geometry/angles.hpp"
#include "slam/calibration_update.hpp"
#include "slam/robocentric_slam.hpp"
#include "slam/worldcentric_slam.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"
#include "tests/slam/observation_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

TrajectorySlamConfig with_range_scale() {
  TrajectorySlamConfig config;
  config.calibration.range_scale = true;
  return config;
}

TrajectorySlamConfig with_compass_deviation() {
  TrajectorySlamConfig config;
  config.calibration.compass_deviation = true;
  return config;
}

TrajectorySlamConfig with_clock_offset() {
  TrajectorySlamConfig config;
  config.calibration.clock_offset = true;
  return config;
}

TrajectorySlamConfig with_dvl_scale() {
  TrajectorySlamConfig config;
  config.calibration.dvl_scale = true;
  return config;
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

// The clock offset moves both scans' frames: its column and the elements' against central
// differences, with the range scale on too (the scale applied after the move).
TEST(CalibrationStates, ObservationJacobiansWithTheClockOffset) {
  const Loop loop = scaled(clock_offset_loop(2, 0.1), 0.97);
  TrajectorySlamConfig both = with_clock_offset();
  both.calibration.range_scale = true;
  Open<WorldCentricSlam> world(with_clock_offset(), GaussianPose2{});
  Open<RoboCentricSlam> robot(both, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  ASSERT_NE(world.parameters()(0), 0.0);
  expect_observation_jacobian(world, 1, 5);
  expect_observation_jacobian(world, 4, 7);
  expect_observation_jacobian(robot, 0, 7);
  robot.velocities().push_back(loop.scans[8].velocity_vehicle);  // as add_scan does first
  robot.predict(loop.scans[8].motion);
  expect_observation_jacobian(robot, 3, 8);
}

// The DVL scale does not enter h (a zero column), and with both parameters each has its own.
TEST(CalibrationStates, ObservationJacobiansWithTheDvlScaleAndBoth) {
  const Loop loop = dvl_scaled(scaled(make_loop(2, false), 0.96), 1.03);
  TrajectorySlamConfig both = with_range_scale();
  both.calibration.dvl_scale = true;
  Open<WorldCentricSlam> world(with_dvl_scale(), GaussianPose2{});
  Open<RoboCentricSlam> robot(both, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  ASSERT_NE(world.parameters()(0), 1.0);
  ASSERT_NE(robot.parameters()(1), 1.0);
  expect_observation_jacobian(world, 1, 5);
  expect_observation_jacobian(robot, 0, 7);
  robot.predict(loop.scans[8].motion);
  expect_observation_jacobian(robot, 1, 8);
}

// The prediction takes in x = (t / k, yaw) of a measured motion (t, yaw): its mean, its
// correlation with k (dx/dk P_kk, dx/dk against central differences) and its covariance
// dx/dm P_m dx/dm^T + dx/dk P_kk dx/dk^T.
TEST(CalibrationStates, DvlScalePredictionAgainstFiniteDifferences) {
  TrajectorySlamConfig config = with_dvl_scale();
  config.calibration.dvl_scale_prior = 1.02;
  config.calibration.dvl_scale_sigma = 0.01;
  const GaussianPose2 motion{Pose2(1.5, -0.4, 0.1),
                             Eigen::Vector3d(0.04, 0.09, 0.0004).asDiagonal()};
  const auto predicted = [&](double k) {
    Open<WorldCentricSlam> slam(config, GaussianPose2{});
    slam.parameters()(0) = k;
    slam.predict(motion);
    return std::make_pair(slam.state().back(), slam.covariance());
  };
  const auto [x, P] = predicted(1.02);
  EXPECT_NEAR(x.x(), 1.5 / 1.02, 1e-12);
  EXPECT_NEAR(x.y(), -0.4 / 1.02, 1e-12);
  EXPECT_EQ(x.yaw(), 0.1);
  const double h = 1e-6;
  const Eigen::Vector3d dx_dk =
      (predicted(1.02 + h).first.vector() - predicted(1.02 - h).first.vector()) / (2 * h);
  ASSERT_EQ(P.rows(), 4);
  EXPECT_LT((P.block<3, 1>(1, 0) - dx_dk * 1e-4).norm(), 1e-9);
  const Eigen::Vector3d J_m(1 / 1.02, 1 / 1.02, 1.0);
  const Eigen::Matrix3d expected =
      J_m.asDiagonal() * motion.cov * J_m.asDiagonal() + dx_dk * 1e-4 * dx_dk.transpose();
  EXPECT_LT((P.bottomRightCorner<3, 3>() - expected).norm(), 1e-9);
}

/// Checks H of compass_residual(b, z) against central differences over the calibration parameters
/// (the first c columns) and the elements 0..b (the next 3(b + 1)).
template <class Filter>
void expect_compass_jacobian(Filter& slam, std::size_t b, double z) {
  Eigen::MatrixXd H;
  slam.compass_residual(slam.state(), b, z, &H);
  const Eigen::Index c = slam.parameters().size();
  ASSERT_EQ(H.cols(), static_cast<Eigen::Index>(c + 3 * (b + 1)));
  const double step = 1e-6;
  for (Eigen::Index col = 0; col < H.cols(); ++col) {
    const auto perturb = [&](double d) {
      if (col < c) {
        slam.parameters()(col) += d;
        return;
      }
      const std::size_t element = static_cast<std::size_t>((col - c) / 3);
      Eigen::Vector3d v = slam.state()[element].vector();
      v((col - c) % 3) += d;
      slam.state()[element] = Pose2(v);
    };
    perturb(step);
    const double plus = slam.compass_residual(slam.state(), b, z, nullptr)(0);
    perturb(-2 * step);
    const double minus = slam.compass_residual(slam.state(), b, z, nullptr)(0);
    perturb(step);
    // The residual is z - h: its difference quotient is -dh.
    EXPECT_NEAR(H(0, col), -(plus - minus) / (2 * step), 1e-6) << "b " << b << " column " << col;
  }
}

// The compass residual z - (psi + a cos(psi) + b sin(psi)), psi the scan's world yaw: its
// Jacobian over the deviation and the elements against central differences, in both filters.
TEST(CalibrationStates, CompassResidualJacobianWithTheDeviation) {
  const Loop loop = with_deviated_compass(make_loop(4, false), 0.62, -3.39, 4, 0.5);
  Open<WorldCentricSlam> world(with_compass_deviation(), GaussianPose2{});
  Open<RoboCentricSlam> robot(with_compass_deviation(), GaussianPose2{});
  for (std::size_t k = 0; k < 12; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  ASSERT_EQ(robot.parameters().size(), 2);  // a, b
  ASSERT_NE(robot.parameters()(1), 0.0);
  expect_compass_jacobian(world, 11, 1.3);
  expect_compass_jacobian(robot, 11, 1.3);
  expect_compass_jacobian(robot, 5, -2.0);
}

// With the deviation: x = (R(-delta/2) t, yaw - delta), delta = (a, b) . (cos psi_k - cos
// psi_k-1, sin psi_k - sin psi_k-1); with the DVL scale too, t / k first. The correlation with
// each parameter (dx/dc_i P_ii, the parameters' prior uncorrelated) against central differences.
TEST(CalibrationStates, DeviationPredictionAgainstFiniteDifferences) {
  TrajectorySlamConfig config = with_compass_deviation();
  config.calibration.dvl_scale = true;
  const GaussianPose2 motion{Pose2(1.5, -0.4, 0.1),
                             Eigen::Vector3d(0.04, 0.09, 0.0004).asDiagonal()};
  const Eigen::Vector2d change(std::cos(1.2) - std::cos(0.3), std::sin(1.2) - std::sin(0.3));
  const Eigen::Vector3d at(1.01, 0.02, -0.05);  // k, a, b (rad)
  const auto predicted = [&](const Eigen::Vector3d& c) {
    Open<RoboCentricSlam> slam(config, GaussianPose2{});
    slam.parameters() = c;
    slam.deviation_change() = change;
    slam.predict(motion);
    return std::make_pair(slam.state().back(), slam.covariance());
  };
  const auto [x, P] = predicted(at);
  const double delta = at.tail<2>().dot(change);
  const Eigen::Vector2d t = Eigen::Rotation2Dd(-delta / 2) * (motion.mean.translation() / 1.01);
  EXPECT_LT((x.translation() - t).norm(), 1e-12);
  EXPECT_NEAR(x.yaw(), 0.1 - delta, 1e-12);
  ASSERT_EQ(P.rows(), 6);
  for (Eigen::Index i = 0; i < 3; ++i) {
    const double h = 1e-6;
    Eigen::Vector3d plus = at, minus = at;
    plus(i) += h;
    minus(i) -= h;
    const Eigen::Vector3d dx_dc =
        (predicted(plus).first.vector() - predicted(minus).first.vector()) / (2 * h);
    EXPECT_LT((P.block<3, 1>(3, i) - dx_dc * P(i, i)).norm(), 1e-9 * P(i, i) + 1e-15)
        << "parameter " << i;
  }
}

// The estimates carried into a calibration.yaml: the deviation and the clock offset add to the
// stated ones; scales have no key, and estimates of those alone carry nothing.
TEST(CalibrationStates, EstimatesAddToTheStatedCalibration) {
  Calibration stated;
  stated.mru.deviation_cos_deg = 0.5;
  stated.sonar.time_offset_s = 0.6;
  stated.sonar.range_scale = 1.02;
  stated.dvl.scale_factor = 0.99;
  const std::optional<Calibration> next =
      calibration_with_estimates(stated, {{"range_scale", 0.97, 0.01},
                                          {"dvl_scale", 1.02, 0.01},
                                          {"clock_offset_s", 0.05, 0.01},
                                          {"compass_deviation_cos_deg", 0.12, 0.1},
                                          {"compass_deviation_sin_deg", -3.4, 0.1}});
  ASSERT_TRUE(next);
  EXPECT_DOUBLE_EQ(next->mru.deviation_cos_deg, 0.62);
  EXPECT_DOUBLE_EQ(next->mru.deviation_sin_deg, -3.4);
  EXPECT_DOUBLE_EQ(next->sonar.time_offset_s, 0.65);
  // The scales estimate what is left after the stated ones: the two multiply.
  EXPECT_DOUBLE_EQ(next->sonar.range_scale, 1.02 * 0.97);
  EXPECT_DOUBLE_EQ(next->dvl.scale_factor, 0.99 * 1.02);
  EXPECT_EQ(next->mru.yaw_offset_deg, stated.mru.yaw_offset_deg);
  EXPECT_EQ(next->dvl.yaw_deg, stated.dvl.yaw_deg);
  EXPECT_TRUE(calibration_with_estimates(stated, {{"range_scale", 0.97, 0.01}}));
  EXPECT_FALSE(calibration_with_estimates(stated, {}));
}

class BothFilters : public ::testing::TestWithParam<std::string> {};

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

/// A calibration parameter a recovery test expects: its name, its true value and the largest
/// standard deviation its estimate may keep (the loop informs it).
struct Expected {
  std::string name;
  double value = 0.0;
  double max_sigma = 0.0;
};

struct Recovery {
  int estimates = 0;     ///< estimates made (loops times parameters)
  double mean_z2 = 0.0;  ///< their mean squared normalised error ((estimate - truth) / sigma)^2
  int better = 0;        ///< loops whose mean error the state lowered
};

/// The robocentric filter with `config` and without any state over loop_of(seed), seeds
/// 1..seeds: the estimates (named and ordered as `expected`, each informed below its max_sigma),
/// their mean squared normalised error, and the loops the state made better. The world-centric
/// filter with the same config runs the same loops and must give the same estimates (within a
/// tenth of their standard deviation): the two parameterisations of one filter.
Recovery recover(unsigned seeds, const std::function<Loop(unsigned)>& loop_of,
                 const TrajectorySlamConfig& config, const std::vector<Expected>& expected) {
  Recovery r;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Loop loop = loop_of(testing::seed(seed));
    const auto estimating = make_filter("robocentric", config);
    const auto world = make_filter("worldcentric", config);
    const auto ignoring = make_filter("robocentric", TrajectorySlamConfig{});
    for (const Scan& scan : loop.scans) {
      estimating->add_scan(scan);
      world->add_scan(scan);
      ignoring->add_scan(scan);
    }
    const std::vector<CalibrationEstimate> c = estimating->calibration();
    const std::vector<CalibrationEstimate> w = world->calibration();
    EXPECT_EQ(c.size(), expected.size());
    EXPECT_EQ(w.size(), expected.size());
    if (c.size() != expected.size() || w.size() != expected.size()) return r;
    std::cout << "seed " << seed << ":";
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(c[i].name, expected[i].name);
      EXPECT_LT(c[i].sigma, expected[i].max_sigma) << "seed " << seed << ": " << c[i].name;
      EXPECT_LT(std::abs(w[i].value - c[i].value), 0.1 * c[i].sigma)
          << "seed " << seed << ": " << c[i].name << ", world-centric " << w[i].value;
      const double z = (c[i].value - expected[i].value) / c[i].sigma;
      r.mean_z2 += z * z;
      ++r.estimates;
      std::cout << " " << c[i].name << " " << c[i].value << " +- " << c[i].sigma << " (z " << z
                << ")";
    }
    const double with_m = mean_error_m(*estimating, loop.truth);
    const double without_m = mean_error_m(*ignoring, loop.truth);
    r.better += with_m < without_m;
    std::cout << ", mean error " << with_m << " m (without the state " << without_m << " m)\n";
  }
  if (r.estimates > 0) r.mean_z2 /= r.estimates;
  return r;
}

/// The statistic of a recovery: a consistent estimate's squared normalised errors are chi-square
/// with 1 degree of freedom, so their mean over n independent estimates lies inside
/// average_chi2_bounds(n, 1, 0.001) but once in a thousand sets of loops (the false-alarm rate).
/// Printed beside it: the factor by which the reported standard deviations may understate the
/// spread before the test catches it nine times in ten.
void expect_consistent(const Recovery& r) {
  ASSERT_GT(r.estimates, 0);
  const auto [lower, upper] = average_chi2_bounds(r.estimates, 1, 0.001);
  const double caught = std::sqrt(upper * r.estimates / chi2_quantile(0.1, r.estimates));
  std::cout << "mean squared normalised error " << r.mean_z2 << " over " << r.estimates
            << " estimates, bounds [" << lower << ", " << upper
            << "]; a standard deviation understated " << caught << " times is caught 9 in 10\n";
  EXPECT_GT(r.mean_z2, lower);
  EXPECT_LT(r.mean_z2, upper);
}

TEST(CalibrationStates, RecoverTheRangeScaleOfScansThatSeeTheWorld4PercentSmall) {
  // Ten loops (seeds 1-10): the estimates of 0.96 consistent (expect_consistent), and the mean
  // error below the filter's without the state in at least 9.
  const Recovery r = recover(10, [](unsigned seed) { return scaled(make_loop(seed, false), 0.96); },
                             with_range_scale(), {{"range_scale", 0.96, 0.02}});
  expect_consistent(r);
  // The loops the state improves, a count of ten: over 20 seed offsets it improved all 200 (a
  // loop it does not: under 1.5 %, one-sided 95 %), so two of ten not improved has probability
  // under 0.93 % and three under 0.04 %.
  EXPECT_GE(r.better, 9);
}

TEST(CalibrationStates, RecoverTheDvlScaleOfMotions3PercentLong) {
  // As above, ten loops: the estimates of 1.03 consistent, the mean error below the filter's
  // without the state in at least 8 (4 of 5 loops before).
  const Recovery r =
      recover(10, [](unsigned seed) { return dvl_scaled(make_loop(seed, false), 1.03); },
              with_dvl_scale(), {{"dvl_scale", 1.03, 0.015}});
  expect_consistent(r);
  // The loops the state improves, a count of ten: over 20 seed offsets it improved all 200 (a
  // loop it does not: under 1.5 %, one-sided 95 %), so two of ten not improved has probability
  // under 0.93 % and three under 0.04 %.
  EXPECT_GE(r.better, 8);
}

TEST(CalibrationStates, RecoverTheCompassDeviation) {
  // The replica's injected deviation (a, b) = (0.62, -3.39) deg, a compass with 0.5 deg of
  // noise, ten loops: the 20 coefficients consistent (expect_consistent), and the mean error below
  // the filter's that takes the compass as calibrated in at least 8 loops. Over 30 loops the
  // normalised errors had means 0.39 and -0.12 and standard deviations 1.05 and 1.26.
  const Recovery r = recover(
      10,
      [](unsigned seed) {
        return with_deviated_compass(make_loop(seed, false), 0.62, -3.39, seed, 0.5);
      },
      with_compass_deviation(),
      {{"compass_deviation_cos_deg", 0.62, 0.5}, {"compass_deviation_sin_deg", -3.39, 0.5}});
  expect_consistent(r);
  // The loops the state improves, a count of ten: over 20 seed offsets it improved all 200 (a
  // loop it does not: under 1.5 %, one-sided 95 %), so two of ten not improved has probability
  // under 0.93 % and three under 0.04 %.
  EXPECT_GE(r.better, 8);
}

TEST(CalibrationStates, RecoverTheSonarClockOffset) {
  // The loop at St. Pere's timing: scans a revolution (13.8 s) apart, so 4 m between them is
  // 0.29 m/s and a corner 6.5 deg/s; the sonar's clock 0.66 s behind (the offset found on the
  // real run), the state's prior the default 0.5 s. The scans carry the dead reckoning's velocity,
  // as a run's do: each scan's own noisy motion over its time, whose error is the motion's the
  // state holds. Ten loops: the estimates of 0.66 s consistent (expect_consistent), each informed
  // below 0.1 s, and the mean error below the filter's without the state in at least 8.
  // Over 20 seed offsets (200 loops): normalised errors of mean -0.25 and sd 1.12 (-0.04 and 1.05
  // with the truth's velocity on the same loops: the filter's own overconfidence), so the mean
  // squared one over ten, 1.26 chi-square(10) / 10 rather than chi-square(10) / 10, passes the
  // 99.9 % bound 3.14 about 0.5 % of the time, not 0.1 %: one offset of 20 did (3.20; 3.5 with the
  // truth's velocity). The state improved the mean error in 199 of the 200 loops: a loop not
  // improved has probability under 2.4 % (one-sided 95 %), three of ten under 0.2 %.
  // Squeezed into 1 s between scans (4 m/s, the same 0.5 s prior: an offset half the time between
  // scans, where a real one is under a twentieth), the dead reckoning's velocity makes 5 of 10
  // loops lock at -0.37 to -0.54 s (sd 0.04-0.07 s, z down to -16.5) for 0.1 s injected, where
  // the truth's velocity recovers all 10 (0.0997-0.1017 +- 0.0016 s), and so does the truth's plus
  // noise of the same size drawn apart. The model takes the velocity as known; on a straight leg,
  // where equal velocities leave tau unobserved, the first matches' velocities differ by the
  // motions' noise alone, and a filter linearised at its estimate reads that as information on tau
  // (0 +- 0.5 -> -0.44 +- 0.25 s from the first two); the corners, then predicted about 50 deg
  // off, fail the gate. Tried there: the velocity from the state's estimate of the motion it
  // shares (with its Jacobian), 0 of 10; the product tau u's second-order variance (var(tau) M
  // Sigma_u M^T, M = d2h/dtau du) added to each match's, 7 of 10 (8 with the velocity from the
  // state). Neither is adopted (docs/trajectory_slam.md, "The sonar clock's offset").
  const Recovery r =
      recover(10,
              [](unsigned seed) {
                return clock_offset_loop(seed, 0.66, ScanVelocity::kDeadReckoning, 13.8);
              },
              with_clock_offset(), {{"clock_offset_s", 0.66, 0.1}});
  expect_consistent(r);
  // The count of loops improved: three of ten not improved under 0.2 % (above).
  EXPECT_GE(r.better, 8);
}

// The compass residual z - (psi + beta + a cos(psi) + b sin(psi)): its Jacobian over the bias,
// the deviation and the elements against central differences, in both filters.
TEST(CalibrationStates, CompassResidualJacobianWithTheHeadingBias) {
  Loop loop = with_deviated_compass(make_loop(5, false), 0.62, -3.39, 5, 0.5);
  with_walking_compass(loop, 0.3, 0.5, 5);
  TrajectorySlamConfig config = with_heading_bias(0.3);
  config.calibration.compass_deviation = true;
  config.calibration.heading_bias_sigma_deg = 1.0;
  Open<WorldCentricSlam> world(config, GaussianPose2{});
  Open<RoboCentricSlam> robot(config, GaussianPose2{});
  for (std::size_t k = 0; k < 12; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  ASSERT_EQ(robot.parameters().size(), 3);  // beta, a, b
  ASSERT_NE(robot.parameters()(0), 0.0);
  expect_compass_jacobian(world, 11, 1.3);
  expect_compass_jacobian(robot, 11, 1.3);
  expect_compass_jacobian(robot, 5, -2.0);
}

// A compass whose bias starts unknown (1 deg from the prior's 0, drawn from the prior) and walks
// 0.3 deg / sqrt(s) under 0.1 deg of white noise, ten loops. Statistics, each at a false alarm of
// 0.001 or less (the world-centric filter on the same loops giving the same bias within a tenth of
// its standard deviation):
// - the bias estimates: mean squared normalised error in the two-sided 99.9 % bounds of
//   chi-square(10) / 10, [0.126, 3.14] (measured 1.24 on average over 30 seed offsets, 0.43-2.39);
// - the last scan's yaw NEES, averaged over the ten loops, against the same filter's on the same
//   loops with a compass that does not walk (calibrated, 0.1 deg): the state should leave the
//   yaw as consistent as the filter is without any walk. Over 30 seed offsets the difference was
//   0.13 on average with a spread of 0.53: bound 0.13 + 3.3 x 0.53 = 1.9 (one-sided). Without
//   the state it is hundreds.
// The filter's own yaw NEES on these loops averages 1.40 over 30 offsets, not 1: its scan matches'
// covariance understates their spread (tests/slam/scan_matching_test.cpp, the cross-covariance
// test: 0.0042 against 0.0050 m^2 in x), which is why this test compares with it rather than with
// chi-square(10) / 10. Was: the bias starting exactly known, the yaw NEES within [0.22, 2.52] (4 of
// 20 offsets failed, on the filter's own inconsistency) and the bias within 2 sd in 8 of 10.
TEST(CalibrationStates, RecoverTheHeadingBiasOfAWalkingCompass) {
  double nees_with = 0.0, nees_without = 0.0, nees_still = 0.0, z2 = 0.0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const WalkingCompassLoops loops = walking_compass_loops(testing::seed(seed));
    const Loop& loop = loops.walking;
    const Loop& still = loops.still;
    const double bias_rad = loops.end_bias_rad;
    const TrajectorySlamConfig config = heading_bias_config();
    const auto estimating = make_filter("robocentric", config);
    const auto world = make_filter("worldcentric", config);
    const auto ignoring = make_filter("robocentric", TrajectorySlamConfig{});
    const auto calibrated = make_filter("robocentric", TrajectorySlamConfig{});
    for (const Scan& scan : loop.scans) {
      estimating->add_scan(scan), world->add_scan(scan), ignoring->add_scan(scan);
    }
    for (const Scan& scan : still.scans) calibrated->add_scan(scan);
    const std::size_t last = loop.scans.size() - 1;
    const auto yaw_nees = [&](const TrajectorySlam& slam) {
      const GaussianPose2 pose = slam.scan_pose_world(last);
      const double e = normalize_angle(pose.mean.yaw() - loop.truth[last].yaw());
      return e * e / pose.cov(2, 2);
    };
    nees_with += yaw_nees(*estimating) / 10.0;
    nees_without += yaw_nees(*ignoring) / 10.0;
    nees_still += yaw_nees(*calibrated) / 10.0;
    const CalibrationEstimate beta = estimating->calibration().at(0);
    z2 += std::pow((beta.value - bias_rad / kDegToRad) / beta.sigma, 2) / 10.0;
    EXPECT_EQ(beta.name, "heading_bias_deg");
    // The world-centric filter, the same filter parameterised otherwise, gives the same bias.
    EXPECT_LT(std::abs(world->calibration().at(0).value - beta.value), 0.1 * beta.sigma)
        << "seed " << seed << ", world-centric " << world->calibration().at(0).value;
    std::cout << "seed " << seed << ": bias " << bias_rad / kDegToRad << " deg, estimated "
              << beta.value << " +- " << beta.sigma << "\n";
  }
  std::cout << "last scan's yaw NEES, 10 loops: " << nees_with << " with the state, "
            << nees_without << " without, " << nees_still << " with a calibrated compass; the "
            << "bias's mean squared normalised error " << z2 << "\n";
  // The statistics named above the test, each at 0.1 % or less: chi-square(10) / 10's two-sided
  // 99.9 % bounds (0.43-2.39 over 20 seed offsets), the yaw NEES's one-sided 3.3-sd margin over
  // the calibrated compass's (differences up to 1.40 over those 20).
  EXPECT_GT(z2, 0.126);
  EXPECT_LT(z2, 3.14);
  EXPECT_LT(nees_with, nees_still + 1.9);
  // The change caught: without the state the yaw NEES is hundreds (269 at least over 20 seed
  // offsets); 10 catches it every time.
  EXPECT_GT(nees_without, 10.0);
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
                         ::testing::Values("robocentric", "worldcentric"));

}  // namespace
}  // namespace msislab
