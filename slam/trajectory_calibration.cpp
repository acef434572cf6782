// The calibration states of trajectory SLAM (docs/trajectory_slam.md, "Calibration states"):
// their priors at the start, the dead-reckoning motion as the state takes it in, x = g(c, m)
// (the DVL scale, the compass deviation's change), the heading bias's walk, the compass's h with
// the bias and the deviation, and the estimates read out. How a match sees the range scale and the
// clock offset is in trajectory_observations.cpp; the updates and the step in trajectory_slam.cpp.
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/angles.hpp"
#include "slam/calibration_model.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab {

TrajectorySlam::TrajectorySlam(const TrajectorySlamConfig& config, const GaussianPose2& start_world)
    : config_(config), start_world_(start_world) {
  const CalibrationStatesConfig& c = config_.calibration;
  std::vector<std::pair<double, double>> priors;  // (mean, sd) in row order
  if (c.range_scale) {
    range_scale_row_ = static_cast<Eigen::Index>(priors.size());
    priors.emplace_back(c.range_scale_prior, c.range_scale_sigma);
  }
  if (c.dvl_scale) {
    dvl_scale_row_ = static_cast<Eigen::Index>(priors.size());
    priors.emplace_back(c.dvl_scale_prior, c.dvl_scale_sigma);
  }
  if (c.clock_offset) {
    clock_row_ = static_cast<Eigen::Index>(priors.size());
    priors.emplace_back(c.clock_offset_prior_s, c.clock_offset_sigma_s);
  }
  if (c.heading_bias) {
    heading_bias_row_ = static_cast<Eigen::Index>(priors.size());
    priors.emplace_back(0.0, c.heading_bias_sigma_deg * kDegToRad);
  }
  if (c.compass_deviation) {
    deviation_row_ = static_cast<Eigen::Index>(priors.size());
    priors.emplace_back(c.compass_deviation_cos_prior_deg * kDegToRad,
                        c.compass_deviation_sigma_deg * kDegToRad);
    priors.emplace_back(c.compass_deviation_sin_prior_deg * kDegToRad,
                        c.compass_deviation_sigma_deg * kDegToRad);
  }
  // The first motion runs from the start, whose heading carries the deviation of its own
  // reading when it was taken from the compass (a start yaw with a variance), none when it is
  // exact (a simulation's truth): the dead reckoning's heading at scan 0 carries d(psi_0).
  const double start_yaw_rad = start_world.mean.yaw();
  previous_deviation_basis_ =
      start_world.cov(2, 2) > 1e-6
          ? Eigen::Vector2d(std::cos(start_yaw_rad), std::sin(start_yaw_rad))
          : Eigen::Vector2d::Zero();
  const auto count = static_cast<Eigen::Index>(priors.size());
  calibration_.resize(count);
  P_ = Eigen::MatrixXd::Zero(count, count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto& [mean, sd] = priors[static_cast<std::size_t>(i)];
    calibration_(i) = mean;
    P_(i, i) = sd * sd;
  }
}

Pose2 TrajectorySlam::calibrated_motion(const Pose2& m, Eigen::Matrix3d& J_m,
                                        Eigen::MatrixXd& J_c) const {
  // The DVL's scale divides the translation; the deviation's change over the motion,
  // (a, b) . deviation_change_, turns it and the heading (slam/calibration_model.hpp).
  const CalibratedMotion g = msislab::calibrated_motion(
      m, dvl_scale_row_ >= 0 ? std::optional(calibration_(dvl_scale_row_)) : std::nullopt,
      deviation_row_ >= 0 ? std::optional<Eigen::Vector2d>(calibration_.segment<2>(deviation_row_))
                          : std::nullopt,
      deviation_change_);
  J_m = g.d_m;
  J_c.setZero(3, calibration_.size());
  if (dvl_scale_row_ >= 0) J_c.col(dvl_scale_row_) = g.d_k;
  if (deviation_row_ >= 0) J_c.middleCols<2>(deviation_row_) = g.d_ab;
  return g.x;
}

void TrajectorySlam::walk_heading_bias(double t_s) {
  if (heading_bias_row_ < 0) return;
  if (previous_scan_t_s_ && t_s > *previous_scan_t_s_) {
    // beta_k = beta_k-1 + w, w independent of the state: only beta's own variance grows. The
    // dead-reckoning motion's heading change also carries w (the compass drove it); over a scan's
    // 13.8 s that is 0.037 deg at 0.01 deg / sqrt(s), against the motion's own heading noise, and
    // left out (docs/trajectory_slam.md).
    const double q =
        std::pow(config_.calibration.heading_bias_walk_deg_per_sqrt_s * M_PI / 180.0, 2);
    P_(heading_bias_row_, heading_bias_row_) += q * (t_s - *previous_scan_t_s_);
  }
  previous_scan_t_s_ = t_s;
}

void TrajectorySlam::note_deviation_change(double compass_yaw_world_rad) {
  // The deviation's change over the motion, at the headings the compass read with the estimated
  // deviation taken out (psi = reading - d(reading), to first order): (a, b) times the change of
  // (cos psi, sin psi) from the motion's start. Unknown (zero) after a scan without a reading.
  deviation_change_.setZero();
  if (deviation_row_ < 0) return;
  double psi = compass_yaw_world_rad;
  if (!std::isfinite(psi)) {
    previous_deviation_basis_.reset();
    return;
  }
  psi -= calibration_.segment<2>(deviation_row_).dot(Eigen::Vector2d(std::cos(psi), std::sin(psi)));
  const Eigen::Vector2d basis(std::cos(psi), std::sin(psi));
  if (previous_deviation_basis_) deviation_change_ = basis - *previous_deviation_basis_;
  previous_deviation_basis_ = basis;
}

Eigen::VectorXd TrajectorySlam::compass_residual(const std::vector<Pose2>& elements, std::size_t b,
                                                 double yaw_world_rad, Eigen::MatrixXd* H) const {
  // z = the MRU heading observes the yaw of scan b in the world: start yaw + the chain's yaw.
  Eigen::MatrixXd H_pose;
  const Pose2 pose = pose_in_start_frame_of(elements, b, H ? &H_pose : nullptr);
  const Eigen::Index c = calibration_.size();
  if (H) {
    H->setZero(1, c + H_pose.cols());
    H->rightCols(H_pose.cols()) = H_pose.row(2);
  }
  double deviation_rad = 0.0;
  if (heading_bias_row_ >= 0) {
    // The MRU reads psi + beta: dh/dbeta = 1.
    deviation_rad += calibration_(heading_bias_row_);
    if (H) (*H)(0, heading_bias_row_) = 1.0;
  }
  if (deviation_row_ >= 0) {
    // The MRU reads psi + a cos(psi) + b sin(psi) for the yaw psi: dh/dpsi = 1 + d'(psi).
    const double yaw_rad = start_world_.mean.yaw() + pose.yaw();
    const Eigen::Vector2d basis(std::cos(yaw_rad), std::sin(yaw_rad));
    const Eigen::Vector2d slope(-std::sin(yaw_rad), std::cos(yaw_rad));
    const Eigen::Vector2d ab = calibration_.segment<2>(deviation_row_);
    deviation_rad += ab.dot(basis);
    if (H) {
      H->block<1, 2>(0, deviation_row_) = basis.transpose();
      H->rightCols(H_pose.cols()) *= 1.0 + ab.dot(slope);
    }
  }
  return Eigen::VectorXd::Constant(
      1, normalize_angle(yaw_world_rad - start_world_.mean.yaw() - pose.yaw() - deviation_rad));
}

std::vector<CalibrationEstimate> TrajectorySlam::calibration() const {
  std::vector<CalibrationEstimate> out;
  if (range_scale_row_ >= 0) {
    const Eigen::Index r = range_scale_row_;
    out.push_back({"range_scale", calibration_(r), std::sqrt(P_(r, r))});
  }
  if (dvl_scale_row_ >= 0) {
    const Eigen::Index r = dvl_scale_row_;
    out.push_back({"dvl_scale", calibration_(r), std::sqrt(P_(r, r))});
  }
  if (clock_row_ >= 0) {
    const Eigen::Index r = clock_row_;
    out.push_back({"clock_offset_s", calibration_(r), std::sqrt(P_(r, r))});
  }
  if (heading_bias_row_ >= 0) {
    const Eigen::Index r = heading_bias_row_;
    out.push_back(
        {"heading_bias_deg", calibration_(r) * kRadToDeg, std::sqrt(P_(r, r)) * kRadToDeg});
  }
  if (deviation_row_ >= 0) {
    const Eigen::Index r = deviation_row_;
    out.push_back({"compass_deviation_cos_deg", calibration_(r) * kRadToDeg,
                   std::sqrt(P_(r, r)) * kRadToDeg});
    out.push_back({"compass_deviation_sin_deg", calibration_(r + 1) * kRadToDeg,
                   std::sqrt(P_(r + 1, r + 1)) * kRadToDeg});
  }
  return out;
}

}  // namespace msislab
