// A synthetic loop for the SLAM back ends' tests: a vehicle drives twice around a walled basin,
// its odometry drifts, and its scans see the walls.
#pragma once

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

#include "geometry/angles.hpp"
#include "geometry/se2.hpp"
#include "slam/scan_builder.hpp"
#include "slam/trajectory_slam.hpp"
#include "tests/draws.hpp"

namespace msislab {

/// Walls of a 40 x 30 m basin plus a pier and a block inside, sampled every 0.4 m.
inline std::vector<Eigen::Vector2d> basin() {
  std::vector<Eigen::Vector2d> points;
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.4);
    for (int i = 0; i <= n; ++i) points.push_back(a + (b - a) * i / n);
  };
  wall({-20, -15}, {20, -15});
  wall({20, -15}, {20, 15});
  wall({20, 15}, {-20, 15});
  wall({-20, 15}, {-20, -15});
  wall({0, 15}, {0, 8});     // a pier
  wall({-6, -4}, {-2, -4});  // a block
  wall({-2, -4}, {-2, -1});
  return points;
}

struct Loop {
  std::vector<Pose2> truth;  ///< scan poses in the world
  std::vector<Scan> scans;
};

/// Scan poses every 4 m around a 24 x 16 m rectangle, twice; each scan sees the basin within
/// 25 m (point noise 0.05 m x noise); motions are the true ones with noise (0.08 m, 0.08 m,
/// 0.6 deg, times noise).
inline Loop make_loop(unsigned seed, bool empty_scans, double noise_scale = 1.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const auto world = basin();
  std::vector<Pose2> truth;
  for (int lap = 0; lap < 2; ++lap) {
    for (int i = 0; i < 6; ++i) truth.emplace_back(-12.0 + 4 * i, -8.0, 0.0);
    for (int i = 0; i < 4; ++i) truth.emplace_back(12.0, -8.0 + 4 * i, M_PI / 2);
    for (int i = 0; i < 6; ++i) truth.emplace_back(12.0 - 4 * i, 8.0, M_PI);
    for (int i = 0; i < 4; ++i) truth.emplace_back(-12.0, 8.0 - 4 * i, -M_PI / 2);
  }
  const Eigen::Vector3d sigma = noise_scale * Eigen::Vector3d(0.08, 0.08, 0.6 * M_PI / 180);
  const double sigma_point_m = 0.05 * noise_scale;
  Loop loop;
  loop.truth = truth;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    Scan scan;
    scan.t_s = static_cast<double>(k);
    const Pose2 true_motion = k == 0 ? truth[0] : truth[k - 1].between(truth[k]);
    const Eigen::Vector3d noise = sigma.cwiseProduct(draws_last_first<3>([&] { return n01(rng); }));
    scan.motion.mean = k == 0 ? true_motion : Pose2(true_motion.vector() + noise);
    scan.motion.cov = k == 0 ? Eigen::Matrix3d::Identity() * 1e-9
                             : Eigen::Matrix3d(sigma.cwiseProduct(sigma).asDiagonal());
    const bool blind = empty_scans && k % 7 == 3;
    for (const auto& p_world : world) {
      const Eigen::Vector2d p = truth[k].inverse().transform(p_world);
      if (blind || p.norm() > 25.0) continue;
      ScanPoint point;
      point.p_m = p + sigma_point_m * draws_last_first<2>([&] { return n01(rng); });
      point.cov = sigma_point_m * sigma_point_m * Eigen::Matrix2d::Identity();
      point.cov_reading = point.cov;
      point.p_vehicle_m = point.p_m;
      scan.points.push_back(point);
    }
    loop.scans.push_back(scan);
  }
  return loop;
}

/// The loop's scans seeing the world s times its size (a sonar whose ranges are s times true).
inline Loop scaled(Loop loop, double s) {
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

/// The loop's dead-reckoning motions as a DVL with scale factor k measures them: k times the true
/// translation (and its noise).
inline Loop dvl_scaled(Loop loop, double k) {
  for (Scan& scan : loop.scans) {
    scan.motion.mean =
        Pose2(k * scan.motion.mean.x(), k * scan.motion.mean.y(), scan.motion.mean.yaw());
    scan.motion.cov.topRows<2>() *= k;
    scan.motion.cov.leftCols<2>() *= k;
  }
  return loop;
}

/// Which velocity a clock-offset loop's scans carry.
enum class ScanVelocity {
  kTruth,          ///< the true one, known exactly
  kDeadReckoning,  ///< the dead reckoning's: the scan's own noisy motion over its time
};

/// The loop's scans, seconds_per_scan apart, as a sonar whose clock is tau_s behind shows them:
/// scan k sees the basin from truth_k (+) tau u_k, u_k its velocity (the last motion over its
/// time, the first scan the next one's; points and noise as make_loop's), and carries u_k or the
/// dead reckoning's estimate of it.
inline Loop clock_offset_loop(unsigned seed, double tau_s,
                              ScanVelocity carried = ScanVelocity::kTruth,
                              double seconds_per_scan = 1.0) {
  Loop loop = make_loop(seed, false);
  std::mt19937 rng(seed + 2000);
  std::normal_distribution<double> n01(0.0, 1.0);
  const std::vector<Eigen::Vector2d> world = basin();
  for (std::size_t k = 0; k < loop.scans.size(); ++k) {
    Scan& scan = loop.scans[k];
    scan.t_s = seconds_per_scan * static_cast<double>(k);
    const std::size_t from = k == 0 ? 0 : k - 1;
    const Eigen::Vector3d u_true =
        loop.truth[from].between(loop.truth[from + 1]).vector() / seconds_per_scan;
    scan.velocity_vehicle =
        carried == ScanVelocity::kTruth
            ? u_true
            : Eigen::Vector3d(loop.scans[from + 1].motion.mean.vector() / seconds_per_scan);
    const Pose2 seen_from = loop.truth[k].compose(Pose2(Eigen::Vector3d(tau_s * u_true)));
    scan.points.clear();
    for (const Eigen::Vector2d& p_world : world) {
      const Eigen::Vector2d p = seen_from.inverse().transform(p_world);
      if (p.norm() > 25.0) continue;
      ScanPoint point;
      point.p_m = p + 0.05 * draws_last_first<2>([&] { return n01(rng); });
      point.cov = 0.05 * 0.05 * Eigen::Matrix2d::Identity();
      point.cov_reading = point.cov;
      point.p_vehicle_m = point.p_m;
      scan.points.push_back(point);
    }
  }
  return loop;
}

/// The filters' config with the compass's heading-bias state on, walking at that density.
inline TrajectorySlamConfig with_heading_bias(double walk_deg_per_sqrt_s) {
  TrajectorySlamConfig config;
  config.calibration.heading_bias = true;
  config.calibration.heading_bias_walk_deg_per_sqrt_s = walk_deg_per_sqrt_s;
  return config;
}

/// The loop with a compass whose bias walks (density walk_deg_per_sqrt_s from start_bias_deg at
/// the first scan, scans 1 s apart) under white noise of sigma_deg; returns the bias at the last
/// scan.
inline double with_walking_compass(Loop& loop, double walk_deg_per_sqrt_s, double sigma_deg,
                                   unsigned seed, double start_bias_deg = 0.0) {
  std::mt19937 rng(seed + 3000);
  std::normal_distribution<double> n01(0.0, 1.0);
  double bias_rad = start_bias_deg * kDegToRad;
  for (std::size_t k = 0; k < loop.scans.size(); ++k) {
    if (k > 0) bias_rad += walk_deg_per_sqrt_s * kDegToRad * n01(rng);
    loop.scans[k].compass_yaw_world_rad =
        loop.truth[k].yaw() + bias_rad + sigma_deg * kDegToRad * n01(rng);
    loop.scans[k].compass_sigma_rad = sigma_deg * kDegToRad;
  }
  return bias_rad;
}

/// The heading-bias recovery tests' loops (tests/slam/calibration_states_test.cpp,
/// tests/slam/pose_graph_heading_bias_test.cpp): make_loop(seed) with a compass whose bias starts
/// at a draw from N(0, 1 deg), the prior those tests give the state (heading_bias_config), and
/// walks 0.3 deg / sqrt(s) under 0.1 deg of white noise; and the same loop with a calibrated
/// compass (no bias, the same noise), the back end's own consistency to compare with.
struct WalkingCompassLoops {
  Loop walking;
  Loop still;
  double end_bias_rad = 0.0;  ///< the walking compass's bias at the last scan
};

inline WalkingCompassLoops walking_compass_loops(unsigned seed) {
  WalkingCompassLoops out;
  out.walking = make_loop(seed, false);
  out.still = out.walking;
  with_walking_compass(out.still, 0.0, 0.1, seed);
  std::mt19937 start_rng(seed + 5000);
  const double start_bias_deg = std::normal_distribution<double>(0.0, 1.0)(start_rng);
  out.end_bias_rad = with_walking_compass(out.walking, 0.3, 0.1, seed, start_bias_deg);
  return out;
}

/// The config that estimates walking_compass_loops' bias: the state walking as the compass does,
/// from a 1 deg prior.
inline TrajectorySlamConfig heading_bias_config() {
  TrajectorySlamConfig config = with_heading_bias(0.3);
  config.calibration.heading_bias_sigma_deg = 1.0;
  return config;
}

/// The one-cycle deviation d(psi) = a cos(psi) + b sin(psi), a and b in deg, in rad.
inline double deviation_rad(double yaw_rad, double a_deg, double b_deg) {
  return (a_deg * std::cos(yaw_rad) + b_deg * std::sin(yaw_rad)) * (M_PI / 180.0);
}

/// The loop with a compass (its readings psi + d(psi) + noise of sigma_deg) whose deviation also
/// shaped the dead reckoning: each motion's heading change reads d(psi_k) - d(psi_k-1) too much
/// (the first, from the exact start, d(psi_0)) and its translation is turned by half of it
/// (docs/trajectory_slam.md).
inline Loop with_deviated_compass(Loop loop, double a_deg, double b_deg, unsigned seed,
                                  double sigma_deg) {
  std::mt19937 rng(seed + 1000);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (std::size_t k = 0; k < loop.scans.size(); ++k) {
    Scan& scan = loop.scans[k];
    const double psi = loop.truth[k].yaw();
    scan.compass_yaw_world_rad =
        psi + deviation_rad(psi, a_deg, b_deg) + sigma_deg * (M_PI / 180.0) * n01(rng);
    scan.compass_sigma_rad = sigma_deg * (M_PI / 180.0);
    // The first motion runs from the exact start (no deviation) to a heading that has it.
    const double delta = deviation_rad(psi, a_deg, b_deg) -
                         (k == 0 ? 0.0 : deviation_rad(loop.truth[k - 1].yaw(), a_deg, b_deg));
    const Eigen::Vector2d t = Eigen::Rotation2Dd(delta / 2.0) * scan.motion.mean.translation();
    scan.motion.mean = Pose2(t.x(), t.y(), scan.motion.mean.yaw() + delta);
  }
  return loop;
}

}  // namespace msislab
