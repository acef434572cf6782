// Scans (paper Sec. II-B; Burguera et al. IROS 2010): an MSIS revolution takes 13.8 s, so the
// readings of its 200 beams were taken from 200 different poses. A scan holds every reading in
// the frame of the revolution's central pose, with the reading noise and the motion uncertainty
// propagated, and the motion from the previous scan frame: the x_k = N(x_hat, P) of the paper's
// state. slam/scan_sequence builds them from the dead reckoning.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/beam_segmentation.hpp"

namespace msislab {

/// A reading in the scan frame.
struct ScanPoint {
  Eigen::Vector2d p_m = Eigen::Vector2d::Zero();  ///< in the scan frame (vehicle at the centre)
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  ///< reading noise + motion uncertainty
  double t_s = 0.0;                               ///< when the beam was taken
  Eigen::Vector2d p_vehicle_m = Eigen::Vector2d::Zero();  ///< the reading in its own vehicle frame
  /// The reading noise alone, in the scan frame: the part of `cov` no other point shares (spIC's
  /// covariance counts only this part as independent; whoever builds points must set it).
  Eigen::Matrix2d cov_reading = Eigen::Matrix2d::Zero();
  /// The motion part of the error is shared by the points of one half of the scan (the beams
  /// before or after the centre ride on the same dead-reckoning error): it is modelled as
  /// distortion * xi_side with xi_side ~ N(0, I) common to the half (docs/scan_matching.md).
  Matrix23d distortion = Matrix23d::Zero();
  int side = 0;  ///< 0: taken before the centre beam, 1: from it on
  /// The sonar head at the beam's time, in the scan frame and in the vehicle frame (the beam's
  /// axis runs from it to the point: slam/beam_footprint.hpp).
  Eigen::Vector2d p_sonar_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d p_vehicle_sonar_m = Eigen::Vector2d::Zero();
};

/// How a beam's pose error loads on its half-scan's shared error xi ~ N(0, I):
/// x_centre_beam error = loading * xi.
struct BeamDistortion {
  int side = 0;
  Eigen::Matrix3d loading = Eigen::Matrix3d::Zero();
};

struct Scan {
  double t_s = 0.0;  ///< time of the central beam (the scan frame's time)
  std::vector<ScanPoint> points;
  /// Motion from the previous scan's frame to this one; for the first scan, from the start pose.
  GaussianPose2 motion;
  std::size_t beams = 0;
  /// The MRU's absolute heading at the scan's time (the vehicle's yaw in the world frame) and its
  /// standard deviation; NaN when there is none.
  double compass_yaw_world_rad = std::numeric_limits<double>::quiet_NaN();
  double compass_sigma_rad = std::numeric_limits<double>::quiet_NaN();
  /// The dead reckoning's mean velocity over the scan's revolution (surge m/s, sway m/s, yaw rate
  /// rad/s; its motion from the first beam to the last over their time): how far the scan as a
  /// whole moves when the sonar's clock is off.
  Eigen::Vector3d velocity_vehicle = Eigen::Vector3d::Zero();
};

struct ScanConfig {
  int beams_per_scan = 200;        ///< one revolution
  double max_compass_gap_s = 1.0;  ///< a scan takes the heading reading nearest its time within
  Eigen::Vector2d p_vehicle_sonar_m =
      Eigen::Vector2d(0.33, 0.0);  ///< the head in the vehicle frame
};

/// The point of a reading in the vehicle frame and its covariance:
/// p = p_sonar + r [cos b, sin b], P = R(b) diag(sigma_r^2, (r sigma_b)^2) R(b)^T.
ScanPoint reading_in_vehicle(const SonarReading& reading, const Eigen::Vector2d& p_vehicle_sonar_m);

/// Appends the readings of one beam to `points`, in the scan frame: p_c = x_cb (+) p_v with
/// P_c = J_pose P_cb J_pose^T + J_p P_v J_p^T, given the beam's vehicle pose x_cb in that frame,
/// and the shared part of the error J_pose * distortion.loading.
void add_scan_points(const std::vector<SonarReading>& readings, const GaussianPose2& x_centre_beam,
                     const Eigen::Vector2d& p_vehicle_sonar_m, std::vector<ScanPoint>& points,
                     const BeamDistortion& distortion = {});

}  // namespace msislab
