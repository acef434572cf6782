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
#include <utility>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/linearisation_probe.hpp"
#include "slam/match_validation.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_front_end.hpp"
#include "slam/scan_matching.hpp"
#include "slam/scan_slam.hpp"
#include "slam/scan_slam_records.hpp"
#include "slam/trajectory_slam_config.hpp"

namespace msislab {

/// A candidate match's record before the distance is set: scan k against scan j, as validated,
/// with the prediction it was made from and its NIS (NaN when it did not reach the gate).
MatchRecord record_of(std::size_t j, std::size_t k, const ValidatedMatch& m,
                      const GaussianPose2& predicted, double nis);

/// An observation z of the pose of the newest scan in the frame of scan `reference`, in the
/// directions whose rows `observed` holds (3 x 3 identity: all; 2 x 3: a direction left out).
struct RelativePoseObservation {
  std::size_t reference = 0;
  Pose2 z;
  Eigen::MatrixXd observed = Eigen::MatrixXd::Identity(3, 3);
  /// Errors in the state that z shares with other matches: z = h(X) + sum loading x_row, x_row the
  /// three parameters from that row of the calibration (a scan's half-scan motion error).
  struct SharedError {
    Eigen::Index row = 0;
    Eigen::Matrix3d loading = Eigen::Matrix3d::Zero();
  };
  std::vector<SharedError> shared = {};
};

/// The first state element observations of scan b involve: the smallest reference + 1.
inline std::size_t first_involved(std::size_t b, const std::vector<RelativePoseObservation>& z) {
  std::size_t first = b;
  for (const RelativePoseObservation& o : z) first = std::min(first, o.reference + 1);
  return first;
}

class TrajectorySlam : public ScanFrontEnd {
 public:
  TrajectorySlam(const TrajectorySlamConfig& config, const GaussianPose2& start_world);

  std::size_t scans() const override { return elements_.size(); }
  /// The calibration states switched on (range_scale, dvl_scale), with their standard deviations.
  std::vector<CalibrationEstimate> calibration() const override;
  bool estimates_dvl_scale() const override { return config_.calibration.dvl_scale; }

  /// The world pose of scan i with its covariance.
  GaussianPose2 scan_pose_world(std::size_t i) const override = 0;
  /// h(X) for scans a < b: the pose of scan b in scan a's frame; with H, its Jacobian with
  /// respect to the state elements a+1..b (3 x 3(b-a)).
  Pose2 relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const {
    return relative_pose_of(elements_, a, b, H);
  }

  /// h(X) of an observation of scan b in scan a's frame: the relative pose, its translation times
  /// the range scale when that is estimated; with H, the Jacobian with respect to the calibration
  /// (its first columns) and the elements a+1..b.
  Pose2 observed_relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const {
    return observed_relative_pose_of(elements_, a, b, H);
  }

  /// The pose of scan b in the start frame (h(X) of an absolute measurement); with H, its
  /// Jacobian with respect to the elements 0..b (3 x 3(b+1)).
  Pose2 pose_in_start_frame(std::size_t b, Eigen::MatrixXd* H) const {
    return pose_in_start_frame_of(elements_, b, H);
  }

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

  /// Tells `observer` of every linearisation the filter makes from now on (a study's;
  /// slam/linearisation_probe.hpp), or no one (nullptr). The observer must outlive the filter's
  /// use of it; it does not change the estimate.
  void set_linearisation_observer(LinearisationObserver* observer) { observer_ = observer; }

 protected:
  /// relative_pose and pose_in_start_frame of the state elements given (the filter's own, or a
  /// study's sample of them of the same length).
  virtual Pose2 relative_pose_of(const std::vector<Pose2>& elements, std::size_t a, std::size_t b,
                                 Eigen::MatrixXd* H) const = 0;
  virtual Pose2 pose_in_start_frame_of(const std::vector<Pose2>& elements, std::size_t b,
                                       Eigen::MatrixXd* H) const = 0;
  /// observed_relative_pose of the state elements given, at the calibration's estimate.
  Pose2 observed_relative_pose_of(const std::vector<Pose2>& elements, std::size_t a, std::size_t b,
                                  Eigen::MatrixXd* H) const;

  /// The stacked A_i (z_i - h_i(X)) of observations of scan b at the state elements given and,
  /// with H, its Jacobian with respect to the calibration (its first columns) and the elements
  /// first..b, first = the smallest reference + 1.
  Eigen::VectorXd stacked_residual(const std::vector<Pose2>& elements, std::size_t b,
                                   const std::vector<RelativePoseObservation>& z,
                                   Eigen::MatrixXd* H) const;
  /// Appends the new motion as the state stores it during the update of its step: the
  /// dead-reckoning motion, its translation divided by the DVL scale when that is estimated
  /// (then correlated with it).
  virtual void predict(const GaussianPose2& motion);
  /// After all updates of a step (the robocentric inversion).
  virtual void finish_step() {}

  /// The covariance of a function of elements [first, first + m) with Jacobian J (3 x 3m).
  Eigen::Matrix3d propagate(std::size_t first, const Eigen::MatrixXd& J) const;
  /// The row (and column) of element i's first coordinate in P_, after the calibration.
  Eigen::Index element_row(std::size_t i) const {
    return calibration_.size() + static_cast<Eigen::Index>(3 * i);
  }
  /// The compass residual z - h(X) of scan b's heading reading (h = its world yaw psi, plus
  /// d(psi) with the deviation estimated) at the state elements given; with H, its Jacobian with
  /// respect to the calibration (its first columns) and the elements 0..b.
  Eigen::VectorXd compass_residual(const std::vector<Pose2>& elements, std::size_t b,
                                   double yaw_world_rad, Eigen::MatrixXd* H) const;
  /// With an observer: tells it of inverting the newest element (the robocentric inversion,
  /// Eq. 11-13), before it is inverted.
  void observe_inversion_linearisation() const;

  TrajectorySlamConfig config_;
  GaussianPose2 start_world_;
  Eigen::VectorXd calibration_;  ///< the parameters switched on, in the rows below; else empty
  Eigen::Index range_scale_row_ = -1;   ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index dvl_scale_row_ = -1;     ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index deviation_row_ = -1;     ///< a's row (b's the next, both rad); -1: not estimated
  Eigen::Index clock_row_ = -1;         ///< its row in calibration_ and P_; -1: not estimated
  Eigen::Index heading_bias_row_ = -1;  ///< its row (rad) in calibration_ and P_; -1: not estimated
  /// For the motion predict() appends: (cos psi_k - cos psi_k-1, sin psi_k - sin psi_k-1) of the
  /// compass headings at its two scans (zero when either has none), which the deviation's change
  /// over the motion is linear in.
  Eigen::Vector2d deviation_change_ = Eigen::Vector2d::Zero();
  std::vector<Pose2> elements_;
  Eigen::MatrixXd P_;  ///< covariance of [calibration_; elements_]

 private:
  // The front end's steps (slam/scan_front_end.hpp).
  const ScanFrontEndConfig& front_end_config() const override { return config_.front_end; }
  void predict_scan(const Scan& scan, const GaussianPose2& motion) override;
  bool update_compass_reading(const Scan& scan, SlamStepStats& stats) override;
  void update_with_matches(std::size_t k, const ScanCandidates& candidates, const Scan& scan,
                           SlamStepStats& stats) override;
  void finish_scan_step(std::size_t k, const Scan& scan) override;

  /// An observation: residual(elements, H) gives the wrapped residual z - h(X) at those state
  /// elements and, with H, its Jacobian with respect to the calibration and the elements
  /// first..b. With observe_linearisation and an observer, tells it of the residual's
  /// linearisation at the prior when the update is accepted.
  /// Returns the window's element count when the update was applied, nullopt when gated out.
  template <class Residual>
  std::optional<std::size_t> update(std::size_t first, std::size_t b, const Residual& residual,
                                    const Eigen::MatrixXd& R, double gate_chi2,
                                    bool observe_linearisation);
  /// Tells the observer of an accepted update's linearisation of its residual at the prior, over
  /// the involved elements first_involved..b (their prior x_involved, covariance P_involved,
  /// the residual's Jacobian H_involved on them; S the innovation covariance).
  template <class Residual>
  void observe_observation_linearisation(std::size_t first_involved, std::size_t b,
                                         const Residual& residual, const Eigen::VectorXd& z_minus_h,
                                         const Eigen::VectorXd& x_involved,
                                         const Eigen::MatrixXd& P_involved,
                                         const Eigen::MatrixXd& H_involved,
                                         const Eigen::MatrixXd& S) const;
  /// With an observer: tells it of the linearisation of the newest scan's pose in the start frame.
  void observe_pose_linearisation() const;
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

  /// With scan_shared_errors: the noise R of a match of scan k against scan j, its own
  /// part (spIC's covariance less the scans' shares the state holds), after adding to the state
  /// what of both scans' errors is not yet in it: each half-scan's motion error (prior N(0, I)),
  /// whose loadings go to `shared`, and with kMotionAndPoints each scan's rigid error for its
  /// points' noise (prior: this match's points' share of it, moved into the scan's frame).
  /// With kNone: the match's covariance.
  Eigen::Matrix3d match_noise(std::size_t j, std::size_t k, const ScanMatchResult& match,
                              std::vector<RelativePoseObservation::SharedError>* shared);
  /// Appends three parameters ~ N(0, cov), uncorrelated, to the calibration rows; their first row.
  Eigen::Index add_shared_error(const Eigen::Matrix3d& cov);
  /// A scan's errors in the state (scan_shared_errors): their rows in calibration_ and P_.
  struct ScanErrors {
    Eigen::Index rigid_row = -1;  ///< e_s, its points' rigid error; -1: not in the state
    Eigen::Matrix3d rigid_prior = Eigen::Matrix3d::Zero();
    std::array<Eigen::Index, 2> half_row{-1, -1};  ///< xi of each half-scan; -1: not in the state
  };
  ScanErrors& scan_errors(std::size_t s);
  /// h with the scans' registration errors: (-)e_a (+) h (+) e_b for those in the state; with H
  /// (on the calibration and the elements, as observed_relative_pose_of's), its Jacobian.
  Pose2 with_scan_errors(const Pose2& h, std::size_t a, std::size_t b, Eigen::MatrixXd* H) const;

  std::vector<std::size_t> group_start_;  ///< first element of each element's correlated group
  std::vector<ScanErrors> scan_errors_;   ///< per scan, with scan_shared_errors
  /// (cos psi, sin psi) of the previous scan's heading (the start's, first); none after a scan
  /// without a compass reading.
  std::optional<Eigen::Vector2d> previous_deviation_basis_;
  std::optional<double> previous_scan_t_s_;    ///< for the heading bias's walk
  LinearisationObserver* observer_ = nullptr;  ///< a study's; none by default
};

}  // namespace msislab
