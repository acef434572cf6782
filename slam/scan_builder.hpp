// Scan building (paper Sec. II-B; Burguera et al. IROS 2010): an MSIS revolution takes 13.8 s, so
// the readings of its 200 beams were taken from 200 different poses. The builder keeps the
// readings history and the transformations history (the dead-reckoning motion between consecutive
// beams, with covariance). When a revolution completes, it expresses every reading in the frame of
// the revolution's central pose, propagating the reading noise and the motion uncertainty, and
// gives the motion between consecutive scan frames: the x_k = N(x_hat, P) of the paper's state.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "slam/beam_segmentation.hpp"
#include "slam/gaussian_pose.hpp"

namespace msislab {

/// A reading in the scan frame.
struct ScanPoint {
  Eigen::Vector2d p_m = Eigen::Vector2d::Zero();  ///< in the scan frame (vehicle at the centre)
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  ///< reading noise + motion uncertainty
  double t_s = 0.0;                               ///< when the beam was taken
  Eigen::Vector2d p_vehicle_m = Eigen::Vector2d::Zero();  ///< the reading in its own vehicle frame
};

struct Scan {
  double t_s = 0.0;  ///< time of the central beam (the scan frame's time)
  std::vector<ScanPoint> points;
  /// Motion from the previous scan's frame to this one; for the first scan, from the vehicle
  /// pose at the first beam.
  GaussianPose2 motion;
  std::size_t beams = 0;
};

struct ScanBuilderConfig {
  int beams_per_scan = 200;  ///< one revolution
  Eigen::Vector2d p_vehicle_sonar_m =
      Eigen::Vector2d(0.33, 0.0);  ///< the head in the vehicle frame
};

/// The point of a reading in the vehicle frame and its covariance:
/// p = p_sonar + r [cos b, sin b], P = R(b) diag(sigma_r^2, (r sigma_b)^2) R(b)^T.
ScanPoint reading_in_vehicle(const SonarReading& reading, const Eigen::Vector2d& p_vehicle_sonar_m);

/// Appends the readings of one beam to `points`, in the scan frame: p_c = x_cb (+) p_v with
/// P_c = J_pose P_cb J_pose^T + J_p P_v J_p^T, given the beam's vehicle pose x_cb in that frame.
void add_scan_points(const std::vector<SonarReading>& readings, const GaussianPose2& x_centre_beam,
                     const Eigen::Vector2d& p_vehicle_sonar_m, std::vector<ScanPoint>& points);

/// The streaming builder for when only per-beam increments are known. It composes them as
/// independent, which is optimistic when they share an error (a velocity-state EKF's);
/// build_scans (slam/scan_sequence) uses exact dead-reckoning clones instead.
class ScanBuilder {
 public:
  explicit ScanBuilder(const ScanBuilderConfig& config);

  /// Adds the next beam: the vehicle motion since the previous beam (in the previous beam's
  /// vehicle frame; for the very first beam, ignored) and the beam's readings. Returns the scan
  /// when this beam completes a revolution.
  std::optional<Scan> add_beam(double t_s, const GaussianPose2& motion_since_previous_beam,
                               const std::vector<SonarReading>& readings);

 private:
  struct Beam {
    double t_s = 0.0;
    GaussianPose2 motion;  ///< from the previous beam
    std::vector<SonarReading> readings;
  };
  Scan build();

  ScanBuilderConfig config_;
  std::vector<Beam> beams_;          ///< the current revolution
  GaussianPose2 after_last_centre_;  ///< motion from the last scan's centre to its last beam
  bool first_scan_ = true;
};

}  // namespace msislab
