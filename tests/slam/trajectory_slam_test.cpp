// Trajectory SLAM, robocentric and world-centric, on a synthetic loop: a vehicle drives twice
// around a walled basin, its odometry drifts, and matching scans against earlier ones pulls the
// trajectory back. Also: the observation Jacobians and the inversion against finite differences,
// the two filters agreeing in the linear limit, the loop-window update equal to the whole-state
// one, and bad or empty scans skipped and counted.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <memory>
#include <random>

#include "slam/pose_graph_slam.hpp"
#include "slam/robocentric_slam.hpp"
#include "slam/worldcentric_slam.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"
#include "tests/draws.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

double final_error_m(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  return (estimate.back().translation() - truth.back().translation()).norm();
}

std::unique_ptr<TrajectorySlam> make_slam(const std::string& method,
                                          const TrajectorySlamConfig& config = {}) {
  if (method == "robocentric") return std::make_unique<RoboCentricSlam>(config, GaussianPose2{});
  return std::make_unique<WorldCentricSlam>(config, GaussianPose2{});
}

std::vector<GaussianPose2> run(ScanSlam& slam, const std::vector<Scan>& scans) {
  for (const Scan& scan : scans) slam.add_scan(scan);
  slam.finish();
  std::vector<GaussianPose2> poses;
  for (std::size_t i = 0; i < slam.scans(); ++i) poses.push_back(slam.scan_pose_world(i));
  return poses;
}

class BothMethods : public ::testing::TestWithParam<std::string> {};

TEST_P(BothMethods, ClosesTheLoopBetterThanOdometry) {
  int better = 0;
  double nees_sum = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Loop loop = make_loop(testing::seed(seed), false);
    const auto slam = make_slam(GetParam());
    std::vector<Pose2> odometry;
    Pose2 chained;
    for (const Scan& scan : loop.scans) {
      chained = chained.compose(scan.motion.mean);
      odometry.push_back(chained);
    }
    const std::vector<GaussianPose2> poses = run(*slam, loop.scans);
    std::vector<Pose2> estimate;
    for (const GaussianPose2& p : poses) estimate.push_back(p.mean);
    const double slam_m = final_error_m(estimate, loop.truth);
    const double odometry_m = final_error_m(odometry, loop.truth);
    std::cout << GetParam() << " seed " << seed << ": final error SLAM " << slam_m
              << " m, odometry " << odometry_m << " m, " << slam->totals().accepted
              << " matches accepted\n";
    EXPECT_GT(slam->totals().accepted, static_cast<int>(loop.scans.size()));
    EXPECT_EQ(slam->totals().skipped, 0);
    // The loop's final error: under 0.29 m in 498 of 500 loops over 100 seed offsets (each
    // filter), the odometry's 0.013-4.0 m; two loops ended 0.39 and 0.49 m off in both filters
    // (offsets 17000 and 47000), so this bound fails about 2 % of streams, above the suite's 1 %
    // per test. The cause, traced at offset 17000: scan 36's motion drew an error in the 99 %
    // innovation gate's tail (each match's NIS 16.8 against 11.34), all three of its candidates
    // were first-lap scans (nearer than scan 35), so every match was gated out and the pose kept
    // 0.32 m of error; the later loop closures then stayed past the gate (NIS 11.7-14.6) while
    // only the consecutive ones passed. The gate rejects a correct match 1 % of the time by design;
    // what fails here is that nothing brings the state back inside it.
    EXPECT_LT(slam_m, 0.3);
    better += slam_m < odometry_m;
    const Eigen::Vector3d e = pose_difference(poses.back().mean, loop.truth.back());
    nees_sum += e.dot(poses.back().cov.inverse() * e);
  }
  // SLAM ended nearer than the odometry in all 1000 loops over 100 seed offsets (a loop where it
  // does not: under 0.3 %, one-sided 95 %), so two of five not improved has probability under
  // 0.01 %.
  EXPECT_GE(better, 4);
  // The final pose's covariance covers its error: the NEES averaged over the 5 runs stays under
  // the two-sided 99% upper bound for 5 runs. It does not always: over 100 seed offsets the two
  // filters' averaged 4.4 (median), not 3, and 26 of the 200 went past the bound (13 %, up to
  // 10.6): the filter is overconfident on this loop, its matches' covariance understating their
  // spread and scans reused across steps (docs/reliability.md). That is the filter's to fix, not
  // this bound's.
  const double anees = nees_sum / 5.0;
  std::cout << "final-pose NEES averaged over 5 runs: " << anees << " (99% upper bound "
            << average_chi2_bounds(5, 3, 0.01).second << ")\n";
  EXPECT_LT(anees, average_chi2_bounds(5, 3, 0.01).second);
}

TEST_P(BothMethods, BadAndEmptyScansAreSkippedAndCounted) {
  Loop loop = make_loop(3, true);
  // Scan 12: its points are not numbers; scan 15: its motion is not a number.
  for (ScanPoint& p : loop.scans[12].points) p.p_m.x() = std::nan("");
  loop.scans[15].motion.mean = Pose2(Eigen::Vector3d::Constant(std::nan("")));
  const auto slam = make_slam(GetParam());
  int expected_skips = 0;
  for (const Scan& scan : loop.scans) {
    const SlamStepStats stats = slam->add_scan(scan);
    const bool bad = scan.points.empty() || &scan == &loop.scans[12] || &scan == &loop.scans[15];
    expected_skips += bad;
    EXPECT_EQ(stats.skipped, bad);
    if (bad) {
      EXPECT_EQ(stats.matched, 0);
    }
  }
  // Not a statistic: the loop is built with every seventh scan blind (6 of 40) and two spoilt
  // here, 8 skips by construction; fewer would mean the test no longer skips what it says.
  EXPECT_GT(expected_skips, 4);
  EXPECT_EQ(slam->totals().skipped, expected_skips);
  EXPECT_EQ(slam->scans(), loop.scans.size());
  const GaussianPose2 last = slam->scan_pose_world(slam->scans() - 1);
  EXPECT_TRUE(last.mean.vector().allFinite());
  EXPECT_TRUE(last.cov.allFinite());
  // The lost motion is bridged by the loop closures that follow it. Not a statistic: the final
  // error is 0.003 m in both filters (this fixed loop); a lost motion left unbridged (its zero
  // mean kept) leaves the rest of the loop about the 4 m step off, which 0.5 m catches.
  EXPECT_LT(final_error_m({last.mean}, loop.truth), 0.5);
}

TEST_P(BothMethods, LoopWindowUpdateEqualsTheWholeStateUpdate) {
  const Loop loop = make_loop(4, false);
  TrajectorySlamConfig whole;
  whole.filter.update_whole_state = true;
  const auto window_slam = make_slam(GetParam()), whole_slam = make_slam(GetParam(), whole);
  int smaller_windows = 0;
  for (const Scan& scan : loop.scans) {
    const SlamStepStats w = window_slam->add_scan(scan), f = whole_slam->add_scan(scan);
    EXPECT_EQ(w.accepted, f.accepted);
    smaller_windows += w.accepted > 0 && w.window_elements < f.window_elements;
  }
  // Not a statistic: the loop's shape decides which steps' windows are smaller than the state
  // (39 of 40 on this loop, both filters); a window that always took the whole state would give 0.
  EXPECT_GT(smaller_windows, 5);
  EXPECT_LT((window_slam->covariance() - whole_slam->covariance()).cwiseAbs().maxCoeff(), 1e-12);
  for (std::size_t i = 0; i < loop.scans.size(); ++i) {
    EXPECT_LT(pose_difference(window_slam->elements()[i], whole_slam->elements()[i]).norm(), 1e-12);
  }
}

TEST_P(BothMethods, MeasuringTheLinearisationChangesNoEstimate) {
  // A linearisation probe samples the state on its own copy: the same estimate to the bit with it
  // as without; epsilon per kind (the inversion only robocentric), small at this noise and larger
  // at ten times it.
  const Loop loop = make_loop(4, false);
  const auto plain = make_slam(GetParam()), measuring = make_slam(GetParam());
  LinearisationProbe probe(50);
  measuring->set_linearisation_observer(&probe);
  const std::vector<GaussianPose2> a = run(*plain, loop.scans), b = run(*measuring, loop.scans);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].mean.vector(), b[i].mean.vector()) << "scan " << i;
    EXPECT_EQ(a[i].cov, b[i].cov) << "scan " << i;
  }
  const SlamTotals& t = measuring->totals();
  const LinearisationTally& observation = probe.tally(Linearisation::kObservation);
  const LinearisationTally& pose = probe.tally(Linearisation::kPose);
  EXPECT_EQ(observation.count, t.accepted);
  EXPECT_EQ(pose.count, static_cast<int>(loop.scans.size()));
  EXPECT_EQ(probe.tally(Linearisation::kInversion).count,
            GetParam() == "robocentric" ? static_cast<int>(loop.scans.size()) : 0);
  // Not statistics on a sample: the probe's mean epsilon here is 2e-7 (observations) and 1e-6
  // (poses) in both filters, four orders under 0.01, and 0.34-0.40 for the poses at ten times the
  // noise (below): the bounds catch a probe that measures something else than the filter's own
  // linearisation error, not a change of this loop's draws.
  EXPECT_LT(*observation.mean(), 0.01);
  EXPECT_LT(*pose.mean(), 0.01);

  const Loop noisy = make_loop(4, false, 10.0);
  const auto noisy_slam = make_slam(GetParam());
  LinearisationProbe noisy_probe(50);
  noisy_slam->set_linearisation_observer(&noisy_probe);
  run(*noisy_slam, noisy.scans);
  EXPECT_GT(*noisy_probe.tally(Linearisation::kPose).mean(), 10.0 * *pose.mean());
}

TEST_P(BothMethods, JointUpdateEqualsSequentialUpdatesWithoutCrossCovariances) {
  // With the headings known exactly (zero yaw variance in every motion) the relative poses are
  // linear in the translations, so stacking two independent observations in one update (Eq. 8)
  // must give what updating with one and then the other gives, to rounding.
  TrajectorySlamConfig config;
  config.front_end.compass_updates = false;
  config.front_end.innovation_gate_chi2 = 1e9;
  const auto sequential = make_slam(GetParam(), config), joint = make_slam(GetParam(), config);
  std::mt19937 rng(3);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (int k = 0; k < 5; ++k) {
    Scan blind;  // no points: the step only predicts
    const Eigen::Vector3d n = draws_last_first<3>([&] { return n01(rng); });
    blind.motion.mean = Pose2(4.0 + 0.3 * n.x(), 0.5 * n.y(), 0.3 * n.z());
    blind.motion.cov = Eigen::Vector3d(0.04, 0.09, 0.0).asDiagonal();
    blind.motion.cov(0, 1) = blind.motion.cov(1, 0) = 0.01;
    sequential->add_scan(blind);
    joint->add_scan(blind);
  }
  const std::size_t b = 4;
  std::vector<RelativePoseObservation> z;
  std::vector<Eigen::Matrix3d> R;
  for (const std::size_t a : {std::size_t{0}, std::size_t{2}}) {
    const Pose2 h = sequential->relative_pose(a, b, nullptr);
    z.push_back(
        {a,
         Pose2(h.vector() +
               (Eigen::Vector3d() << 0.5 * draws_last_first<2>([&] { return n01(rng); }), 0.01)
                   .finished()),
         Eigen::MatrixXd::Identity(3, 3)});
    Eigen::Matrix3d cov = Eigen::Vector3d(0.02, 0.03, 1e-4).asDiagonal();
    cov(0, 2) = cov(2, 0) = 5e-4;
    R.push_back(cov);
  }
  // The second observes two directions only (a direction left out by the validation).
  z[1].observed = Eigen::MatrixXd::Identity(3, 3).topRows(2);
  const Eigen::MatrixXd R1 = z[1].observed * R[1] * z[1].observed.transpose();
  const double prior_trace = sequential->covariance().trace();
  ASSERT_TRUE(sequential->update_relative_poses(b, {z[0]}, R[0]));
  ASSERT_TRUE(sequential->update_relative_poses(b, {z[1]}, R1));
  Eigen::MatrixXd R_stacked = Eigen::MatrixXd::Zero(5, 5);
  R_stacked.topLeftCorner<3, 3>() = R[0];
  R_stacked.bottomRightCorner<2, 2>() = R1;
  ASSERT_TRUE(joint->update_relative_poses(b, z, R_stacked));
  EXPECT_LT((sequential->covariance() - joint->covariance()).cwiseAbs().maxCoeff(), 1e-9);
  for (std::size_t i = 0; i <= b; ++i) {
    EXPECT_LT(pose_difference(sequential->elements()[i], joint->elements()[i]).norm(), 1e-9);
  }
  // An observation must be of b in an earlier scan's frame.
  EXPECT_FALSE(
      joint->update_relative_poses(b, {{b, Pose2(), Eigen::MatrixXd::Identity(3, 3)}}, R[0]));
  EXPECT_FALSE(joint->update_relative_poses(b + 1, {z[0]}, R[0]));
  // The updates did change the state: the check is not of two untouched filters.
  EXPECT_LT(joint->covariance().trace(), 0.8 * prior_trace);
}

TEST_P(BothMethods, CorrelatedMatchesMoveTheStateLessThanIndependentOnes) {
  // Two observations that share part of their errors carry less information than two
  // independent ones and more than one alone: the posterior covariance of the joint update lies
  // between the two.
  TrajectorySlamConfig config;
  config.front_end.compass_updates = false;
  config.front_end.innovation_gate_chi2 = 1e9;
  std::mt19937 rng(5);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<Scan> blind(4);
  for (Scan& scan : blind) {
    const Eigen::Vector3d n = draws_last_first<3>([&] { return n01(rng); });
    scan.motion.mean = Pose2(3.0 + 0.3 * n.x(), 0.4 * n.y(), 0.05 * n.z());
    scan.motion.cov = Eigen::Vector3d(0.04, 0.09, 1e-3).asDiagonal();
  }
  const Eigen::Matrix3d C = Eigen::Vector3d(0.05, 0.05, 4e-4).asDiagonal();
  double trace[3];
  for (int variant = 0; variant < 3; ++variant) {
    const auto slam = make_slam(GetParam(), config);
    for (const Scan& scan : blind) slam->add_scan(scan);
    const Pose2 h = slam->relative_pose(1, 3, nullptr);
    std::vector<RelativePoseObservation> z(2, {1, h, Eigen::MatrixXd::Identity(3, 3)});
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(6, 6);
    R.topLeftCorner<3, 3>() = C;
    R.bottomRightCorner<3, 3>() = C;
    if (variant == 1) R.topRightCorner<3, 3>() = R.bottomLeftCorner<3, 3>() = 0.5 * C;
    if (variant == 2) {
      ASSERT_TRUE(slam->update_relative_poses(3, {z[0]}, C));
    } else {
      ASSERT_TRUE(slam->update_relative_poses(3, z, R));
    }
    trace[variant] = slam->covariance().trace();
  }
  // Independent < half-correlated < one observation.
  EXPECT_LT(trace[0], trace[1]);
  EXPECT_LT(trace[1], trace[2]);
}

TEST(PoseGraphSlam, ClosesTheLoopLikeTheFilters) {
  // The same scans through the pose graph: it accepts as many matches as the filter (the same
  // front end, a wider prediction), ends the second lap near the truth, and its smoothed
  // trajectory is no worse than what it knew online.
  const Loop loop = make_loop(1, false);
  PoseGraphSlam graph(ScanFrontEndConfig{}, CalibrationStatesConfig{}, PoseGraphSlamConfig{},
                      GaussianPose2{});
  RoboCentricSlam filter(TrajectorySlamConfig{}, GaussianPose2{});
  const std::vector<GaussianPose2> smoothed = run(graph, loop.scans);
  const std::vector<GaussianPose2> filtered = run(filter, loop.scans);
  std::vector<Pose2> odometry, smoothed_poses, filtered_poses;
  Pose2 dead_reckoning;
  for (const Scan& scan : loop.scans)
    odometry.push_back(dead_reckoning = dead_reckoning + scan.motion.mean);
  for (const GaussianPose2& p : smoothed) smoothed_poses.push_back(p.mean);
  for (const GaussianPose2& p : filtered) filtered_poses.push_back(p.mean);
  EXPECT_GT(graph.totals().accepted, static_cast<int>(loop.scans.size()));
  EXPECT_GE(graph.totals().accepted, filter.totals().accepted - 2);
  EXPECT_EQ(graph.matches_downweighted(), 0);
  EXPECT_FALSE(filter.matches_downweighted());
  const double graph_m = final_error_m(smoothed_poses, loop.truth);
  EXPECT_LT(graph_m, 0.5 * final_error_m(odometry, loop.truth));
  EXPECT_LT(graph_m, 2.0 * final_error_m(filtered_poses, loop.truth) + 0.05);
  const std::optional<std::vector<GaussianPose2>> online = graph.online_poses();
  ASSERT_TRUE(online && online->size() == loop.scans.size());
  double online_sum = 0.0, smoothed_sum = 0.0;
  for (std::size_t k = 0; k < loop.truth.size(); ++k) {
    online_sum += ((*online)[k].mean.translation() - loop.truth[k].translation()).norm();
    smoothed_sum += (smoothed[k].mean.translation() - loop.truth[k].translation()).norm();
  }
  EXPECT_LE(smoothed_sum, online_sum + 0.01 * static_cast<double>(loop.truth.size()));
  // Online, the newest scan's pose is the smoothed one at its own step: the last ones agree.
  EXPECT_LT(pose_difference(online->back().mean, smoothed.back().mean).norm(), 1e-6);
  EXPECT_FALSE(filter.online_poses());
}

TEST(TrajectorySlam, FiltersAgreeInTheLinearLimit) {
  // With noise 1e-4 of the usual, linearisation errors vanish and the two parameterisations of
  // the same Gaussian give the same world poses and covariances.
  const Loop loop = make_loop(5, false, 1e-4);
  WorldCentricSlam world(TrajectorySlamConfig{}, GaussianPose2{});
  RoboCentricSlam robot(TrajectorySlamConfig{}, GaussianPose2{});
  const std::vector<GaussianPose2> w = run(world, loop.scans), r = run(robot, loop.scans);
  EXPECT_EQ(world.totals().accepted, robot.totals().accepted);
  EXPECT_GT(world.totals().accepted, static_cast<int>(loop.scans.size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    EXPECT_LT(pose_difference(w[i].mean, r[i].mean).norm(), 1e-7) << "scan " << i;
    const double scale = w[i].cov.norm();
    EXPECT_LT((w[i].cov - r[i].cov).norm(), 1e-3 * scale) << "scan " << i;
  }
}

/// Exposes the robocentric filter's steps and state for finite differences.
class OpenRoboCentric : public RoboCentricSlam {
 public:
  using RoboCentricSlam::finish_step;
  using RoboCentricSlam::predict;
  using RoboCentricSlam::RoboCentricSlam;
  std::vector<Pose2>& state() { return elements_; }
  Eigen::MatrixXd& P() { return P_; }
};

class OpenWorldCentric : public WorldCentricSlam {
 public:
  using WorldCentricSlam::predict;
  using WorldCentricSlam::WorldCentricSlam;
  std::vector<Pose2>& state() { return elements_; }
};

/// Checks H (3 x 3(b-a)) of h = relative_pose(a, b) against central differences over the state
/// elements a+1..b, and that it has no other columns.
template <class Filter>
void expect_jacobian_matches(Filter& slam, std::size_t a, std::size_t b) {
  Eigen::MatrixXd H;
  slam.relative_pose(a, b, &H);
  ASSERT_EQ(H.cols(), static_cast<Eigen::Index>(3 * (b - a)));
  const double step = 1e-6;
  for (Eigen::Index c = 0; c < H.cols(); ++c) {
    const std::size_t element = a + 1 + static_cast<std::size_t>(c / 3);
    const Pose2 saved = slam.state()[element];
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(c % 3) = step;
    slam.state()[element] = Pose2(saved.vector() + d);
    const Pose2 plus = slam.relative_pose(a, b, nullptr);
    slam.state()[element] = Pose2(saved.vector() - d);
    const Pose2 minus = slam.relative_pose(a, b, nullptr);
    slam.state()[element] = saved;
    const Eigen::Vector3d numeric = pose_difference(plus, minus) / (2 * step);
    EXPECT_LT((H.col(c) - numeric).norm(), 1e-6) << "a " << a << " b " << b << " column " << c;
  }
}

/// Checks the Jacobian of pose_in_start_frame(b) against central differences over elements 0..b.
template <class Filter>
void expect_start_frame_jacobian_matches(Filter& slam, std::size_t b) {
  Eigen::MatrixXd H;
  slam.pose_in_start_frame(b, &H);
  ASSERT_EQ(H.cols(), static_cast<Eigen::Index>(3 * (b + 1)));
  const double step = 1e-6;
  for (Eigen::Index c = 0; c < H.cols(); ++c) {
    const std::size_t element = static_cast<std::size_t>(c / 3);
    const Pose2 saved = slam.state()[element];
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(c % 3) = step;
    slam.state()[element] = Pose2(saved.vector() + d);
    const Pose2 plus = slam.pose_in_start_frame(b, nullptr);
    slam.state()[element] = Pose2(saved.vector() - d);
    const Pose2 minus = slam.pose_in_start_frame(b, nullptr);
    slam.state()[element] = saved;
    EXPECT_LT((H.col(c) - pose_difference(plus, minus) / (2 * step)).norm(), 1e-6)
        << "b " << b << " column " << c;
  }
}

TEST(TrajectorySlam, CompassObservationJacobians) {
  const Loop loop = make_loop(2, false);
  OpenWorldCentric world(TrajectorySlamConfig{}, GaussianPose2{});
  OpenRoboCentric robot(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  expect_start_frame_jacobian_matches(world, 7);
  expect_start_frame_jacobian_matches(world, 3);
  expect_start_frame_jacobian_matches(robot, 7);
  robot.predict(loop.scans[8].motion);  // the raw newest element, as during a step
  expect_start_frame_jacobian_matches(robot, 8);
}

TEST_P(BothMethods, CompassBoundsTheHeadingOfABlindRun) {
  // No scan sees anything: the chain's heading is the odometry's, whose yaw errors (0.6 deg a
  // step, as its covariance says) walk to 3.8 deg over the 40 steps; the compass (1 deg) holds
  // it near its steady state, 0.67 deg.
  Loop loop = make_loop(testing::seed(6), false);
  const double sigma_rad = M_PI / 180.0;
  std::mt19937 rng(testing::seed(6));
  std::normal_distribution<double> n01(0.0, 1.0);
  for (std::size_t k = 0; k < loop.scans.size(); ++k) {
    Scan& scan = loop.scans[k];
    scan.points.clear();
    scan.compass_yaw_world_rad = normalize_angle(loop.truth[k].yaw() + sigma_rad * n01(rng));
    scan.compass_sigma_rad = sigma_rad;
  }
  TrajectorySlamConfig without;
  without.front_end.compass_updates = false;
  const auto with_compass = make_slam(GetParam()), blind = make_slam(GetParam(), without);
  const std::vector<GaussianPose2> a = run(*with_compass, loop.scans), b = run(*blind, loop.scans);
  const auto z = [&](const GaussianPose2& estimate) {
    return normalize_angle(estimate.mean.yaw() - loop.truth.back().yaw()) /
           std::sqrt(estimate.cov(2, 2));
  };
  std::cout << GetParam() << ": final yaw error over its sd " << z(a.back())
            << " with the compass (sd " << std::sqrt(a.back().cov(2, 2)) * 180 / M_PI << " deg), "
            << z(b.back()) << " without (sd " << std::sqrt(b.back().cov(2, 2)) * 180 / M_PI
            << " deg); compass readings accepted " << with_compass->totals().compass_accepted
            << "\n";
  // Statistics of a filter whose model holds, each at a false alarm of 0.001:
  // - each reading is gated out with probability 0.01 (the 99 % gate), so 5 or more of the 40
  //   are with probability 0.0008: at least 36 are accepted;
  // - the final yaw error over its reported sd is N(0, 1): |z| < 3.29, with and without the
  //   compass. Caught: a compass update with the wrong sign or weight, a covariance that does
  //   not shrink (the variance check, exact: 0.45 against 14 deg^2).
  EXPECT_GE(with_compass->totals().compass_accepted, static_cast<int>(loop.scans.size()) - 4);
  EXPECT_LT(std::abs(z(a.back())), 3.29);  // N(0, 1): false alarm 0.001
  EXPECT_LT(std::abs(z(b.back())), 3.29);
  EXPECT_LT(a.back().cov(2, 2), b.back().cov(2, 2) / 10.0);
  // Was: the odometry turned 0.5 deg too far at every step, a drift its covariance did not
  // hold, and the compass had to bring the heading within 3 deg. In 7 of 20 seed offsets it
  // did not: one reading gated out on a large step, the drift grows linearly while the gate
  // grows as the square root of the steps, and every later reading is gated out (15 of 40
  // accepted, 14 deg off at the end). That is a finding about the gate under a drift the model
  // does not hold (docs/reliability.md), not a tail of a statistic.
}

TEST(TrajectorySlam, WorldCentricObservationJacobian) {
  const Loop loop = make_loop(2, false);
  OpenWorldCentric slam(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) slam.add_scan(loop.scans[k]);
  expect_jacobian_matches(slam, 1, 5);
  expect_jacobian_matches(slam, 0, 7);
  expect_jacobian_matches(slam, 6, 7);
  // h is the composition of the motions in between.
  Pose2 chain;
  for (std::size_t j = 2; j <= 5; ++j) chain = chain.compose(slam.elements()[j]);
  EXPECT_LT(pose_difference(slam.relative_pose(1, 5, nullptr), chain).norm(), 1e-12);
}

TEST(TrajectorySlam, RoboCentricObservationJacobianDuringAndAfterTheStep) {
  const Loop loop = make_loop(2, false);
  OpenRoboCentric slam(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) slam.add_scan(loop.scans[k]);
  // After the step every element is inverted: e_i is scan i-1 seen from scan i.
  ASSERT_TRUE(slam.newest_inverted());
  expect_jacobian_matches(slam, 1, 7);
  expect_jacobian_matches(slam, 6, 7);
  expect_jacobian_matches(slam, 2, 4);
  // During the step the newest element is the raw motion (delayed inversion, Eq. 2).
  slam.predict(loop.scans[8].motion);
  ASSERT_FALSE(slam.newest_inverted());
  expect_jacobian_matches(slam, 1, 8);
  expect_jacobian_matches(slam, 7, 8);
  expect_jacobian_matches(slam, 0, 8);
  // h = (-)(e_7 (+) ... (+) e_2) (+) e_8 is scan 8 seen from scan 1: the same pose as the true
  // motions chained, up to the odometry noise.
  Pose2 c;
  for (std::size_t i = 7; i >= 2; --i) c = c.compose(slam.state()[i]);
  EXPECT_LT(pose_difference(slam.relative_pose(1, 8, nullptr), c.inverse().compose(slam.state()[8]))
                .norm(),
            1e-12);
  // Not a statistic: the filter's error here is centimetres; a chain composed in the wrong order
  // or left uninverted lands metres away (the seven motions cover 28 m and turn 90 deg).
  EXPECT_LT((slam.relative_pose(1, 8, nullptr).translation() -
             loop.truth[1].between(loop.truth[8]).translation())
                .norm(),
            1.0);
}

TEST(TrajectorySlam, RoboCentricInversionMovesTheCovarianceByItsJacobian) {
  const Loop loop = make_loop(2, false);
  OpenRoboCentric slam(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 12; ++k) slam.add_scan(loop.scans[k]);
  slam.predict(loop.scans[12].motion);
  // Correlate the newest element with the others, as an update would.
  const Eigen::Index n = slam.P().rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(3, n - 3).setConstant(0.1);
  slam.P() = A * slam.P() * A.transpose();
  const Pose2 raw = slam.state().back();
  const Eigen::MatrixXd P_before = slam.P();
  slam.finish_step();
  // Eq. 11-13 against a numeric Jacobian of the inversion.
  const double step = 1e-6;
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(c) = step;
    J.col(c) =
        pose_difference(Pose2(raw.vector() + d).inverse(), Pose2(raw.vector() - d).inverse()) /
        (2 * step);
  }
  Eigen::MatrixXd G = Eigen::MatrixXd::Identity(n, n);
  G.bottomRightCorner<3, 3>() = J;
  EXPECT_LT(pose_difference(slam.state().back(), raw.inverse()).norm(), 1e-15);
  EXPECT_LT((slam.P() - G * P_before * G.transpose()).cwiseAbs().maxCoeff(), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(TrajectorySlam, BothMethods,
                         ::testing::Values("robocentric", "worldcentric"));

}  // namespace
}  // namespace msislab
