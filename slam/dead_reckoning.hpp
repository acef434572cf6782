// Dead reckoning: an EKF fusing DVL bottom velocities and MRU heading (Ribas et al. 2008,
// "Underwater SLAM in man-made structured environments", Sec. 3: constant-velocity model, DVL
// velocity and compass heading updates). State [x_m, y_m, yaw_rad, u_mps, v_mps, r_radps]: the
// vehicle pose in the world frame and its surge, sway and yaw-rate velocities in the vehicle frame.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/navigation.hpp"

namespace msislab {

struct DeadReckoningConfig {
  double dvl_sigma_mps = 0.2;               ///< DVL bottom-velocity white noise per axis, m/s
  double heading_sigma_rad = M_PI / 180.0;  ///< heading white noise, rad (1 deg)
  /// Surge/sway acceleration noise density, m/s^2/sqrt(Hz). The default brings the mean DVL NIS on
  /// the St. Pere logs to its expected 2, so the filter follows the velocity without lagging it
  /// (docs/dead_reckoning.md, "Choosing the noise levels", has the measured NIS).
  double accel_sigma_mps2 = 0.05;
  double yaw_accel_sigma_radps2 = 0.02;       ///< yaw acceleration noise density, rad/s^2/sqrt(Hz)
  double initial_velocity_sigma_mps = 0.3;    ///< prior on u, v at the start, m/s
  double initial_yaw_rate_sigma_radps = 0.1;  ///< prior on r at the start, rad/s
  /// DVL innovation gate on the NIS (e.g. 13.82 = chi-square 2 DOF at 99.9%); <= 0 disables it.
  /// Off by default: the St. Pere DVL noise is heavy-tailed, so a gate rejects far more than its
  /// tail probability and throws away real motion (docs/dead_reckoning.md, "Choosing the noise
  /// levels", has the measured rejection rate).
  double dvl_gate_chi2 = 0.0;
  /// The heading reading's bias beta, a random walk of this density (deg per root second): the
  /// MRU reads yaw + beta + white noise. 0: no bias (the heading noise is white).
  double heading_bias_walk_deg_per_sqrt_s = 0.0;
  /// beta's standard deviation at the start, deg (0: the compass is right at the start).
  double heading_bias_sigma_deg = 0.0;
  /// The DVL's scale factor k (it reads k times the true velocity, after calibration.yaml's
  /// dvl.scale_factor) is 1 with this standard deviation: constant, and unobservable from these
  /// sensors alone. Its error moves the position by (k - 1) times the distance dead-reckoned, so
  /// the poses and motions carry sigma^2 d d^T (a considered parameter, not a state). 0: known.
  double dvl_scale_sigma = 0.0;
};

/// x, y, yaw, u, v, r and the heading reading's bias beta.
constexpr int kDeadReckoningStates = 7;
using DeadReckoningVector = Eigen::Matrix<double, kDeadReckoningStates, 1>;
using DeadReckoningMatrix = Eigen::Matrix<double, kDeadReckoningStates, kDeadReckoningStates>;

class DeadReckoningEkf {
 public:
  /// Starts at a known pose (mean and covariance) at time t_s with unknown velocities.
  /// p_vehicle_dvl_m is the DVL lever arm in the vehicle frame.
  DeadReckoningEkf(const DeadReckoningConfig& config, const Eigen::Vector2d& p_vehicle_dvl_m,
                   const StampedPose& initial);

  /// Constant-velocity prediction to time t_s (no-op when t_s is not later than the state).
  void predict(double t_s);
  /// DVL update, z = [u - r y_dvl, v + r x_dvl]. Returns the normalized innovation squared
  /// (NIS, chi-square 2 DOF when consistent); the update is skipped when the NIS exceeds the gate.
  double update_dvl(const DvlVelocity& dvl);
  /// Heading update, z = yaw + beta with the innovation wrapped. Returns the NIS (chi-square 1
  /// DOF).
  double update_heading(const HeadingReading& heading);

  double time() const { return t_s_; }
  const DeadReckoningVector& state() const { return x_; }
  const DeadReckoningMatrix& covariance() const { return P_; }
  /// The vehicle pose in the world frame with its 3x3 marginal covariance.
  StampedPose pose() const;

  /// Stochastic cloning: remembers the current pose estimate in a slot, frozen, and keeps the
  /// correlation of the state's error with its error, so that the motion from here on,
  /// (-)x_mark (+) x_now between the two filtered estimates, has its exact covariance. Each slot's
  /// correlation evolves on its own, so slots can mark different times.
  static constexpr int kCloneSlots = 2;
  void mark(int slot = 0);
  /// The motion since the slot's last mark(), in the marked pose's frame: (-)x_mark (+) x_now,
  /// with the covariance of the pair (J_mark P_mm J_mark^T + J_now P_nn J_now^T + cross terms).
  /// Chained over consecutive marks, these motions compose back to the filtered trajectory.
  GaussianPose2 motion_since_mark(int slot = 0) const;

 private:
  template <int M>
  double update(const Eigen::Matrix<double, M, 1>& innovation,
                const Eigen::Matrix<double, M, kDeadReckoningStates>& H,
                const Eigen::Matrix<double, M, M>& R, double gate_chi2);

  DeadReckoningConfig config_;
  Eigen::Vector2d p_vehicle_dvl_m_;
  Eigen::Vector2d p_start_world_m_ = Eigen::Vector2d::Zero();  ///< where the integration began
  double t_s_ = 0.0;
  DeadReckoningVector x_ = DeadReckoningVector::Zero();
  DeadReckoningMatrix P_ = DeadReckoningMatrix::Zero();
  // A clone: the estimate at the slot's last mark() (frozen), its error covariance and the
  // cross-covariance of the state's error with it.
  struct Clone {
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, kDeadReckoningStates, 3> P_x =
        Eigen::Matrix<double, kDeadReckoningStates, 3>::Zero();
  };
  Clone clones_[kCloneSlots];
};

struct DeadReckoningResult {
  std::vector<StampedPose> trajectory;  ///< one pose per heading reading after the start
  int dvl_used = 0;
  int dvl_rejected = 0;  ///< by the innovation gate
  int heading_used = 0;
  double dvl_mean_nis = 0.0;      ///< mean NIS of the DVL innovations; 2 when consistent
  double heading_mean_nis = 0.0;  ///< mean NIS of the heading innovations; 1 when consistent
};

/// Runs the EKF over a navigation log from `initial` on (earlier measurements are ignored),
/// processing measurements in time order.
DeadReckoningResult run_dead_reckoning(const NavigationLog& log, const DeadReckoningConfig& config,
                                       const Eigen::Vector2d& p_vehicle_dvl_m,
                                       const StampedPose& initial);

}  // namespace msislab

namespace msislab {

/// Dead reckoning sampled at given times, e.g. the sonar beams'.
struct OdometrySample {
  double t_s = 0.0;
  GaussianPose2 motion;  ///< since the previous sample (the first: since the start), its frame
  StampedPose pose;      ///< the vehicle in the world frame, marginal covariance
  /// The motion since the last key sample before this one (the first: since the start), with its
  /// exact covariance from a clone kept across all the samples in between. On a key sample it
  /// reaches back to the previous key.
  GaussianPose2 motion_since_key;
  bool is_key = false;
};

/// Which samples are keys: indices first, first + every, first + 2 every, ...
struct KeySamples {
  std::size_t first = 0;
  std::size_t every = 0;  ///< 0: no keys
  bool is_key(std::size_t i) const { return every > 0 && i >= first && (i - first) % every == 0; }
};

/// Runs the EKF from `initial` and samples it at the increasing times_s (times before the start
/// give the start pose and no motion). Each motion is the difference of the filtered poses at
/// consecutive samples (so the motions compose back to the dead-reckoning trajectory), with its
/// exact covariance from a frozen clone.
std::vector<OdometrySample> odometry_at(const NavigationLog& log, const DeadReckoningConfig& config,
                                        const Eigen::Vector2d& p_vehicle_dvl_m,
                                        const StampedPose& initial,
                                        const std::vector<double>& times_s,
                                        const KeySamples& keys = {});

/// The reference baseline: plain integration of the DVL velocities, each held until the next DVL
/// sample and rotated by the heading reading nearest in time. No covariance (zero).
std::vector<StampedPose> integrate_velocities(const NavigationLog& log, const StampedPose& initial);

}  // namespace msislab
