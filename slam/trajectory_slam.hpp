// Trajectory SLAM over relative motions between scans (paper Sec. III-IV; docs/trajectory_slam.md).
// The state is a chain of n relative motions X = [x_0, ..., x_{n-1}] with its full covariance;
// element i links scan i-1 and scan i (element 0 links the start pose and scan 0). Each new scan:
//   predict:   the dead-reckoning motion is appended, uncorrelated with the past (paper Eq. 2);
//   associate: past scans whose estimated centre lies within gamma of the new one (Eq. 3-4);
//   observe:   z = spIC(scan_j, scan_k) ~ h(X), the pose of scan k in scan j's frame (Eq. 5-8);
//   update:    an iterated EKF (Eq. 9-10) gated on the innovation's NIS.
// How the elements are stored is what the two variants differ in: the world-centric one keeps
// x_i = pose of scan i in scan i-1's frame (a chain from the world forward); the robocentric one
// keeps the inverses, the chain from the current robot back to the world, and inverts each new
// motion only after its update (delayed inversion, Eq. 11-13).
//
// Updating only the loop (the paper's remark): an observation between scans j and k involves
// elements j+1..k. Motions enter uncorrelated and an update correlates only the elements of its
// window, so the elements form contiguous groups with no correlation between groups. The update of
// the window "group of j+1 up to k" is then exactly the full EKF update, at a cost that grows with
// the loop's length instead of the whole state.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/linearisation_error.hpp"
#include "slam/match_validation.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_matching.hpp"
#include "slam/scan_slam.hpp"
#include "slam/scan_slam_records.hpp"

namespace msislab {

/// Calibration the filter estimates with the trajectory (docs/trajectory_slam.md, "Calibration
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

struct TrajectorySlamConfig {
  double association_distance_m = 10.0;  ///< gamma: match past scans closer than this (m)
  int max_matches_per_scan = 3;          ///< the nearest candidates first
  int min_scan_gap = 1;     ///< match scans at least this many steps back (1: the previous one too)
  int iekf_iterations = 5;  ///< relinearisations of the update (1 = plain EKF)
  double innovation_gate_chi2 = 11.34;  ///< 3 DOF, 99%: inconsistent matches are rejected
  /// Update each scan's world heading with the MRU's absolute heading (a relative chain forgets
  /// that the compass bounds the heading error; docs/trajectory_slam.md).
  bool compass_updates = true;
  double compass_gate_chi2 = 6.63;  ///< 1 DOF, 99%
  /// Update a step's matches together (paper Eq. 8): stacked, with the cross-covariances of
  /// matches that share the newest scan, all linearised at the step's prediction. Off: one match
  /// after the other, each as if independent and from the state the previous one left.
  bool joint_update = false;
  /// The joint update's cross-covariances between a step's matches (spIC's loadings on the newest
  /// scan's errors, shared_current_covariance). Off: taken as zero (for checks and studies).
  bool match_cross_covariance = true;
  /// Update every element instead of the loop's window (the same result at a higher cost; for
  /// checks and timing).
  bool update_whole_state = false;
  /// Measure the linearisation error epsilon (slam/linearisation_error.hpp) of every accepted
  /// match's update, of the robocentric inversion and of the newest scan's pose, with this many
  /// samples each (a study's diagnostic, in metrics.json; it does not change the estimate). 0: off.
  int linearisation_samples = 0;
  ScanMatchConfig matching;
  MatchValidationConfig validation;  ///< checks a match passes before the update (Sec. below)
  CalibrationStatesConfig calibration;
};

/// A candidate match's record before the distance is set: scan k against scan j, as validated,
/// with the prediction it was made from and its NIS (NaN when it did not reach the gate).
MatchRecord record_of(std::size_t j, std::size_t k, const ValidatedMatch& m,
                      const GaussianPose2& predicted, double nis);

/// Data association (paper Eq. 3-4), shared by every back end: the past scans j <= k - min_scan_gap
/// (k the newest, points.size() - 1) whose distance to the newest lies below gamma and which
/// have enough points to match, nearest first, at most max_matches_per_scan, as (distance, j).
std::vector<std::pair<double, std::size_t>> nearest_candidates(
    const std::vector<double>& distances_m, const std::vector<std::vector<ScanPoint>>& points,
    const TrajectorySlamConfig& config);

/// An observation z of the pose of the newest scan in the frame of scan `reference`, in the
/// directions whose rows `observed` holds (3 x 3 identity: all; 2 x 3: a direction left out).
struct RelativePoseObservation {
  std::size_t reference = 0;
  Pose2 z;
  Eigen::MatrixXd observed = Eigen::MatrixXd::Identity(3, 3);
};

/// The first state element observations of scan b involve: the smallest reference + 1.
inline std::size_t first_involved(std::size_t b, const std::vector<RelativePoseObservation>& z) {
  std::size_t first = b;
  for (const RelativePoseObservation& o : z) first = std::min(first, o.reference + 1);
  return first;
}

class TrajectorySlam : public ScanSlam {
 public:
  TrajectorySlam(const TrajectorySlamConfig& config, const GaussianPose2& start_world);

  /// Adds a scan (its points in its own frame, its motion from the previous scan's frame) and
  /// closes the loops it finds. A scan with a non-finite motion is chained with a zero motion of
  /// very large covariance (the filter loses track instead of failing); non-finite points are
  /// dropped.
  SlamStepStats add_scan(const Scan& scan) override;

  std::size_t scans() const override { return elements_.size(); }
  const SlamTotals& totals() const override { return totals_; }
  /// The calibration states switched on (range_scale, dvl_scale), with their standard deviations.
  std::vector<CalibrationEstimate> calibration() const override;
  bool estimates_dvl_scale() const override { return config_.calibration.dvl_scale; }

  /// The world pose of scan i with its covariance.
  GaussianPose2 scan_pose_world(std::size_t i) const override = 0;
  /// h(X) for scans a < b: the pose of scan b in scan a's frame; with H, its Jacobian with
  /// respect to the state elements a+1..b (3 x 3(b-a)).
  virtual Pose2 relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const = 0;

  /// h(X) of an observation of scan b in scan a's frame: the relative pose, its translation times
  /// the range scale when that is estimated; with H, the Jacobian with respect to the calibration
  /// (its first columns) and the elements a+1..b.
  Pose2 observed_relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const;

  /// The pose of scan b in the start frame (h(X) of an absolute measurement); with H, its
  /// Jacobian with respect to the elements 0..b (3 x 3(b+1)).
  virtual Pose2 pose_in_start_frame(std::size_t b, Eigen::MatrixXd* H) const = 0;

  /// The measurement update add_scan applies (public for front ends of their own and checks):
  /// the observations z_i of scan b's pose in scan reference_i's frame (reference_i < b), stacked
  /// as A_i z_i ~ A_i h_i(X) with the stacked covariance R (blocks A_i cov(z_i, z_j) A_j^T), in one
  /// iterated EKF update (paper Eq. 8-10), gated on the stacked NIS at the configured gate's
  /// probability. Returns the number of state elements the update's window held when the state
  /// was updated; nullopt when it was not (also when b is not a scan or a reference is not before
  /// it).
  std::optional<std::size_t> update_relative_poses(std::size_t b,
                                                   const std::vector<RelativePoseObservation>& z,
                                                   const Eigen::MatrixXd& R);

  /// The state elements as stored (see the derived classes); the covariance of the whole state,
  /// the calibration parameters first (calibration_parameters()), then the elements.
  const std::vector<Pose2>& elements() const { return elements_; }
  const Eigen::MatrixXd& covariance() const { return P_; }
  const Eigen::VectorXd& calibration_parameters() const { return calibration_; }

 protected:
  /// Appends the new motion as the state stores it during the update of its step: the
  /// dead-reckoning motion, its translation divided by the DVL scale when that is estimated
  /// (then correlated with it).
  virtual void predict(const GaussianPose2& motion);
  /// After all updates of a step (the robocentric inversion).
  virtual void finish_step() {}
  /// Estimated distance of each past scan j < k to the newest scan k.
  virtual std::vector<double> distances_to_newest() const = 0;

  /// The covariance of a function of elements [first, first + m) with Jacobian J (3 x 3m).
  Eigen::Matrix3d propagate(std::size_t first, const Eigen::MatrixXd& J) const;
  /// The row (and column) of element i's first coordinate in P_, after the calibration.
  Eigen::Index element_row(std::size_t i) const {
    return calibration_.size() + static_cast<Eigen::Index>(3 * i);
  }
  /// The compass residual z - h(X) of scan b's heading reading (h = its world yaw psi, plus
  /// d(psi) with the deviation estimated); with H, its Jacobian with respect to the calibration
  /// (its first columns) and the elements 0..b.
  Eigen::VectorXd compass_residual(std::size_t b, double yaw_world_rad, Eigen::MatrixXd* H) const;
  /// With linearisation_samples > 0: tallies epsilon of inverting the newest element (the
  /// robocentric inversion, Eq. 11-13), before it is inverted.
  void measure_inversion_linearisation();

  TrajectorySlamConfig config_;
  GaussianPose2 start_world_;
  Eigen::VectorXd calibration_;  ///< the parameters switched on, in the rows below; else empty
  Eigen::Index range_scale_row_ = -1;   ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index dvl_scale_row_ = -1;     ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index deviation_row_ = -1;     ///< a's row (b's the next, both rad); -1: not estimated
  Eigen::Index clock_row_ = -1;         ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index heading_bias_row_ = -1;  ///< its row (rad) in calibration_ and P_; -1: not estimated
  std::vector<Eigen::Vector3d> velocities_;  ///< each scan's Scan::velocity_vehicle
  /// For the motion predict() appends: (cos psi_k - cos psi_k-1, sin psi_k - sin psi_k-1) of the
  /// compass headings at its two scans (zero when either has none), which the deviation's change
  /// over the motion is linear in.
  Eigen::Vector2d deviation_change_ = Eigen::Vector2d::Zero();
  std::vector<Pose2> elements_;
  Eigen::MatrixXd P_;  ///< covariance of [calibration_; elements_]

 private:
  /// An observation: the wrapped residual z - h(X) and, with H, its Jacobian with respect to the
  /// elements first..b.
  /// With measure_linearisation (and linearisation_samples > 0), tallies epsilon of the residual
  /// at the prior when the update is accepted.
  /// Returns the window's element count when the update was applied, nullopt when gated out.
  template <class Residual>
  std::optional<std::size_t> update(std::size_t first, std::size_t b, const Residual& residual,
                                    const Eigen::MatrixXd& R, double gate_chi2,
                                    bool measure_linearisation);
  /// With linearisation_samples > 0: tallies epsilon of the newest scan's pose in the start frame.
  void measure_pose_linearisation();
  /// Every state element and the covariance are finite (checked after each stage of a step).
  bool state_finite() const;
  /// The step's validated matches of scan k against the candidates, one update after the other.
  void update_sequentially(std::size_t k, const std::vector<std::size_t>& candidates,
                           SlamStepStats& stats);
  /// The same matches, all from the prediction and in one update (paper Eq. 8).
  void update_jointly(std::size_t k, const std::vector<std::size_t>& candidates,
                      SlamStepStats& stats);
  /// spIC of scan k against scan j from the state's prediction, then its validation; the
  /// prediction (h(X), H P H^T) in `predicted`.
  ValidatedMatch match(std::size_t j, std::size_t k, GaussianPose2& predicted) const;
  /// The stacked A_i (z_i - h_i(X)) of observations of scan b and, with H, its Jacobian with
  /// respect to the calibration (its first columns) and the elements first..b, first = the
  /// smallest reference + 1.
  Eigen::VectorXd stacked_residual(std::size_t b, const std::vector<RelativePoseObservation>& z,
                                   Eigen::MatrixXd* H) const;
  /// The NIS of observations of scan b against the state: r^T (H P H^T + R)^-1 r.
  double innovation_nis(std::size_t b, const std::vector<RelativePoseObservation>& z,
                        const Eigen::MatrixXd& R) const;
  /// The MRU heading as an observation of scan b's yaw; as update().
  std::optional<std::size_t> update_compass(std::size_t b, double yaw_world_rad, double sigma_rad);

  /// The heading bias's walk from the previous scan to a scan at t_s: its variance grows by
  /// q (t_s - t_previous); the first scan starts it at its prior.
  void walk_heading_bias(double t_s);
  /// Sets deviation_change_ for the motion to a scan with this compass reading (NaN: none).
  void note_deviation_change(double compass_yaw_world_rad);
  /// The motion as the state takes it in, x = g(c, m), with its Jacobians dg/dm (3 x 3) and dg/dc
  /// (3 x c): the DVL scale divides the translation, the deviation's change turns it.
  Pose2 calibrated_motion(const Pose2& m, Eigen::Matrix3d& J_m, Eigen::MatrixXd& J_c) const;

  std::vector<std::size_t> group_start_;  ///< first element of each element's correlated group
  /// (cos psi, sin psi) of the previous scan's heading (the start's, first); none after a scan
  /// without a compass reading.
  std::optional<Eigen::Vector2d> previous_deviation_basis_;
  std::optional<double> previous_scan_t_s_;  ///< for the heading bias's walk
  std::vector<std::vector<ScanPoint>> points_;
  SlamTotals totals_;
  std::mt19937_64 linearisation_rng_{0x6c696e656172ULL};  ///< fixed: the same run, the same bytes
};

}  // namespace msislab
