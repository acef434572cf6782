// spIC: probabilistic scan matching of two scans with uncertain points and an uncertain initial
// guess (Burguera, Gonzalez, Oliver 2008; Montesano et al. 2005; docs/scan_matching.md). Finds the
// pose q of the current scan's frame in the reference scan's frame:
//   E-step: each current point p_j, moved by the guess, q (+) p_j, with covariance
//           J_q P_q J_q^T + J_p C_j J_p^T, is associated with the reference point a_i of least
//           Mahalanobis distance, gated by a chi-square value (2 DOF), and optionally only when
//           p_j is also the current point nearest to a_i (reciprocal);
//   M-step: q minimises sum_j e_j^T W_j^-1 e_j, e_j = q (+) p_j - a_i, W_j = A_i + J_p C_j J_p^T,
//           by Gauss-Newton; repeat until the step is negligible.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/line_normals.hpp"
#include "slam/scan_builder.hpp"

namespace msislab {

struct ScanMatchConfig {
  double association_gate_chi2 = 9.21;  ///< chi-square, 2 DOF (99%)
  int max_iterations = 50;
  int min_inliers = 8;          ///< fewer associations: the match is not valid
  double tolerance_m = 1e-4;    ///< convergence: translation step below this...
  double tolerance_rad = 1e-5;  ///< ...and rotation step below this
  /// Scale the covariance by the residual's variance factor s^2 = chi^2 / (2n - 3) when above 1
  /// (point-to-point residuals on sparse sonar points are larger than the point covariances say).
  bool scale_covariance_by_residual = true;
  /// The covariance counts the errors points share: a reference point's noise is shared by every
  /// current point associated with it, and each half-scan's dead-reckoning error by all its
  /// points; cov = H^-1 A H^-1 (a sandwich, as Censi's) instead of H^-1, which takes every
  /// residual as independent and is overconfident (docs/scan_matching.md).
  bool shared_point_errors = true;
  /// The covariance takes the residual of a pair whose reference point lies on a line (its
  /// neighbours' scatter is thin) along the line's normal only, n^T (q (+) p_j - a_i) (Censi's
  /// point-to-line), so it is large along the directions the geometry leaves unconstrained (the
  /// axis of a straight canal); point-to-point residuals report information along a wall that
  /// the scans do not hold (docs/scan_matching.md).
  bool point_to_line_covariance = false;
  /// The estimate minimises the same point-to-line residuals (its H may then be near-singular in
  /// a corridor; Gauss-Newton steps along the unconstrained direction are not damped).
  bool point_to_line_estimate = false;
  LineNormalConfig line;  ///< how a line is told from clutter around each reference point
  /// Keep a pair (p_j, a_i) only when p_j is also the current point nearest to a_i (mutual
  /// nearest neighbours). The current scan sees past the end of each wall stretch the reference
  /// saw; those points have no counterpart there and, all paired with the reference's last points,
  /// pull the estimate back towards a shorter motion. On by default: one-way association turns
  /// that bias into drift along a canal and an overconfident filter (docs/scan_matching.md,
  /// "Reciprocal association", has the measured effect).
  bool reciprocal_association = true;
};

/// How a match's error loads on the current scan's own errors, to first order at the solution and
/// with the covariance's residual scale: dq = sum_j point[j] e_j + sum_side half[side] xi_side +
/// (terms in the reference scan's errors), e_j the current point j's noise of covariance
/// `cov_reading` (`cov` when the point errors are taken as independent) and xi_side ~ N(0, I) the
/// half-scan's shared motion error. Two matches of one current scan share these errors.
struct CurrentScanLoading {
  std::vector<Eigen::Matrix<double, 3, 2>> point;  ///< per current point (zero: not associated)
  std::array<Eigen::Matrix3d, 2> half{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  bool whole_point_covariance = false;  ///< e_j has the point's `cov`, not `cov_reading`
};

struct ScanMatchResult {
  GaussianPose2 estimate;  ///< q: the current scan's frame in the reference's frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< H = sum J^T W^-1 J at the end
  bool valid = false;  ///< enough associations and a well-posed H
  bool converged = false;
  int iterations = 0;
  int inliers = 0;
  double chi2 = 0.0;                   ///< sum e^T W^-1 e at the end
  CurrentScanLoading current_loading;  ///< set when valid
  /// The parts of estimate.cov each scan's own errors cause (its points' reading noise and its
  /// half-scans' motion errors), with the same residual scale; the rest of the covariance is the
  /// pairs' own (the surfaces' sampling). Every match of a scan shares that scan's part
  /// (docs/trajectory_slam.md, "Scan registration errors"). Set when valid.
  Eigen::Matrix3d current_share = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d reference_share = Eigen::Matrix3d::Zero();
  /// The estimate's loading on the reference scan's half-scan motion errors xi_side ~ N(0, I), as
  /// current_loading.half is on the current scan's (with the residual scale; zero without
  /// shared point errors).
  std::array<Eigen::Matrix3d, 2> reference_half{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
};

/// Matches `current` against `reference` from the guess (its covariance gates the association).
ScanMatchResult match_scans(const std::vector<ScanPoint>& reference,
                            const std::vector<ScanPoint>& current, const GaussianPose2& guess,
                            const ScanMatchConfig& config);

/// The cross-covariance E[dq_a dq_b^T] of two valid matches of the same current scan (against
/// different references, whose errors are independent): the errors of the current scan they
/// share, through each match's loading (docs/trajectory_slam.md, "Joint update"). For a match
/// with itself it is the part of its covariance that the current scan causes.
Eigen::Matrix3d shared_current_covariance(const ScanMatchResult& a, const ScanMatchResult& b,
                                          const std::vector<ScanPoint>& current);

}  // namespace msislab
