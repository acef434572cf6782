// build_scans on a noise-free straight run: the vehicle goes east at 0.5 m/s with a wall 10 m to
// port; beams every 0.5 s, 10 per scan. Scan motions are the dead-reckoning centre-to-centre
// motions, the points land on the wall, and point covariances grow away from the centre.
#include "slam/scan_sequence.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

namespace msislab {
namespace {

struct StraightRun {
  NavigationLog navigation;
  std::vector<BeamReadings> beams;
  StampedPose start;
};

StraightRun straight_run(double duration_s) {
  StraightRun run;
  for (double t = 0.1; t <= duration_s; t += 1.0 / 1.5)
    run.navigation.dvl.push_back({t, {0.5, 0.0}});
  for (double t = 0.05; t <= duration_s; t += 0.1) run.navigation.heading.push_back({t, 0.0});
  for (double t = 0.25; t <= duration_s; t += 0.5) {
    // Looking to port from the head (0.33 m ahead of the origin): the wall y = 10 at range 10.
    run.beams.push_back({t, {{t, 10.0, M_PI / 2, 0.1, 0.02}}});
  }
  run.start.pose.cov = Eigen::Vector3d(1e-9, 1e-9, 1e-6).asDiagonal();
  return run;
}

TEST(ScanSequence, StraightRunGivesKnownScans) {
  // 61 s: 12 full revolutions and two beams more, which give the last revolution's first beam
  // its mirror (at the very end of the data the mirror is clamped to the last sample).
  const StraightRun run = straight_run(61.0);
  ScanConfig config;
  config.beams_per_scan = 10;
  const std::vector<PlacedScan> scans = build_scans(
      run.beams, run.navigation, DeadReckoningConfig{}, Eigen::Vector2d::Zero(), run.start, config);
  ASSERT_EQ(scans.size(), run.beams.size() / 10);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const Scan& scan = scans[k].scan;
    // The scan frame is the vehicle at the central beam (index 5 of the revolution).
    EXPECT_EQ(scan.t_s, run.beams[10 * k + 5].t_s);
    EXPECT_EQ(scans[k].centre_world.t_s, scan.t_s);
    EXPECT_EQ(scan.points.size(), 10u);
    EXPECT_GT(scan.motion.cov.determinant(), 0.0) << "scan " << k;
    // Motions are the dead-reckoning poses' differences (the first from the start pose).
    const Pose2 from = k == 0 ? run.start.pose.mean : scans[k - 1].centre_world.pose.mean;
    EXPECT_LT(
        pose_difference(scan.motion.mean, from.between(scans[k].centre_world.pose.mean)).norm(),
        1e-9);
    if (k < 2) continue;  // the filter learns the velocity in the first seconds
    // One revolution: 10 beams x 0.5 s x 0.5 m/s = 2.5 m east. Tolerance 2 cm.
    EXPECT_NEAR(scan.motion.mean.x(), 2.5, 0.02) << "scan " << k;
    EXPECT_NEAR(scan.motion.mean.y(), 0.0, 1e-3) << "scan " << k;
    EXPECT_NEAR(scan.motion.mean.yaw(), 0.0, 1e-6) << "scan " << k;
    // Compensated points lie on the wall y = 10, spread along it over the revolution's 2.5 m.
    for (const ScanPoint& p : scan.points) EXPECT_NEAR(p.p_m.y(), 10.0, 0.02);
    EXPECT_NEAR(scan.points.back().p_m.x() - scan.points.front().p_m.x(), 9 * 0.25, 0.02);
    // The central beam carries only the reading noise; uncertainty grows away from it.
    EXPECT_NEAR(scan.points[5].cov(0, 0), (10.0 * 0.02) * (10.0 * 0.02), 1e-9);
    EXPECT_NEAR(scan.points[5].cov(1, 1), 0.1 * 0.1, 1e-9);
    for (std::size_t i = 6; i < 10; ++i) {
      EXPECT_GT(scan.points[i].cov.trace(), scan.points[i - 1].cov.trace()) << "beam " << i;
    }
    for (std::size_t i = 5; i-- > 0;) {
      EXPECT_GT(scan.points[i].cov.trace(), scan.points[i + 1].cov.trace()) << "beam " << i;
    }
  }
  // The world points all lie on the wall.
  for (const Eigen::Vector2d& p : world_points({scans.begin() + 2, scans.end()})) {
    EXPECT_NEAR(p.y(), 10.0, 0.05);
  }
}

TEST(ScanSequence, BeamsBeforeTheStartAndAnIncompleteLastRevolutionAreDropped) {
  StraightRun run = straight_run(30.0);
  run.start.t_s = 5.0;  // beams before 5 s have no navigation yet
  ScanConfig config;
  config.beams_per_scan = 10;
  const auto scans = build_scans(run.beams, run.navigation, DeadReckoningConfig{},
                                 Eigen::Vector2d::Zero(), run.start, config);
  // Beams from 5.25 s to 29.75 s: 50 beams, 5 scans; the first centre is the 6th beam kept.
  ASSERT_EQ(scans.size(), 5u);
  EXPECT_DOUBLE_EQ(scans.front().scan.t_s, 5.25 + 5 * 0.5);
}

}  // namespace
}  // namespace msislab
