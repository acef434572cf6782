// The calibration states every scan back end can estimate beside the trajectory (the filters and
// the pose graph), read from the `trajectory_slam.calibration` section of a SLAM config
// (docs/formats.md).
#pragma once

namespace msislab {

/// Calibration a back end estimates with the trajectory (docs/trajectory_slam.md, "Calibration
/// states"): each switched on leads the state as an additive parameter with a Gaussian prior.
struct CalibrationStatesConfig {
  /// The sonar's range scale s: the scans' geometry is s times the true one (a sound speed s
  /// times the water's, or echoes placed nearer than the surfaces by a fixed fraction), so a match
  /// observes s times the true translation between two scans and the true rotation.
  bool range_scale = false;
  double range_scale_prior = 1.0;
  double range_scale_sigma = 0.05;  ///< the prior's standard deviation
  /// The DVL's scale factor k: the DVL measures k times the true velocity, so a dead-reckoning
  /// motion's translation is k times the true one; the filter takes in (t / k, yaw). With
  /// range_scale also on, only their ratio is observable from matches: the priors split it.
  bool dvl_scale = false;
  double dvl_scale_prior = 1.0;
  double dvl_scale_sigma = 0.02;  ///< the prior's standard deviation
  /// The compass's one-cycle deviation left after the dataset's calibration, d(psi) = a cos(psi)
  /// + b sin(psi): the MRU reads psi + d(psi). It enters the compass update (h = yaw + d(yaw))
  /// and the dead-reckoning motions, whose heading change carries d(psi_k) - d(psi_k-1).
  bool compass_deviation = false;
  double compass_deviation_cos_prior_deg = 0.0;  ///< a's prior mean, deg
  double compass_deviation_sin_prior_deg = 0.0;  ///< b's prior mean, deg
  double compass_deviation_sigma_deg = 3.0;      ///< the prior's standard deviation of each, deg
  /// The sonar clock's offset tau left after calibration.yaml's: the beams were sent tau later
  /// than their times say, so scan i shows the world from the vehicle at t_i + tau, its frame
  /// moved by tau times the vehicle's velocity over the revolution, u_i; a match observes
  /// (-)(tau u_j) (+) h (+) (tau u_k).
  bool clock_offset = false;
  double clock_offset_prior_s = 0.0;
  double clock_offset_sigma_s = 0.5;  ///< the prior's standard deviation, s
  /// The compass's heading bias beta left after calibration.yaml's: the MRU reads psi + beta,
  /// beta a random walk from 0 (as the simulated MRU's bias). The compass update observes
  /// yaw + beta, so the compass no longer pins the heading tighter than the walk allows; its
  /// constant part is not observable from the vehicle's own sensors (its prior stays), its change
  /// since an earlier scan is, through the matches that return to that scan. Its model is the
  /// dead reckoning's (DeadReckoningConfig::heading_bias_*; the config file has it there only).
  bool heading_bias = false;
  double heading_bias_sigma_deg = 0.0;  ///< the prior's standard deviation (0: known), deg
  /// The walk's density: beta's variance grows by its square times the time between scans.
  double heading_bias_walk_deg_per_sqrt_s = 0.0;
};

}  // namespace msislab
