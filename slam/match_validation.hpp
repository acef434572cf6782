// Match validation: a spIC result is checked before the filter sees it (docs/trajectory_slam.md,
// "Match validation"). spIC reports the minimum it reached and a
// covariance from the curvature of its cost with the associations held fixed. Both can be wrong:
//   - along a straight corridor the scans hold no information along the axis. The fixed-association
//     curvature still reports some (sparse points paired point-to-point with points that have no
//     true counterpart), and the solution stays where it was started, so the match "confirms" the
//     prediction with a covariance a few decimetres wide;
//   - with sparse or repetitive returns the minimum reached may be a wrong one.
// The test here restarts spIC from its own solution moved +-d (agreement from several starting
// guesses) along the translation direction the reference's walls constrain least (the smallest
// eigenvector of the scatter of their normals, sum n n^T: a corridor's axis); with too few
// wall-like points, along both axes of the match's covariance. Gauss-Newton on a cost with one
// minimum comes back; on a cost that is flat along a direction it stays where it starts:
//   - a restart that keeps more than half of its offset along the direction it was moved in shows
//     the scans do not fix that direction. The match keeps the directions it does observe (across
//     the corridor and the heading): a reduced measurement A z, A R A^T, with A (2 x 3) of
//     orthonormal rows;
//   - a restart that ends elsewhere in the directions kept (beyond the match's covariance at the
//     chi-square probability configured, and with the scan's points still a good part of the
//     offset away) shows the minimum is not unique: the match is rejected.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_matching.hpp"

namespace msislab {

struct MatchValidationConfig {
  /// d: the restarts begin this far from the solution (m), either side along the direction
  /// tested, or 3 standard deviations of the match there if more; 0 turns the restart test off.
  /// Larger than the points' spacing on a wall, so a restart does not stop on the sampling pattern.
  double restart_offset_m = 1.5;
  /// A restart that ends further than this fraction of d from the solution along the direction it
  /// was moved in did not come back: the scans do not fix that direction. Gauss-Newton on a cost
  /// with a unique minimum comes back in a step or two; on a flat one it stays where it starts.
  double max_kept_fraction = 0.5;
  /// A restart that ends away from the solution in the directions found observed, beyond this
  /// chi-square probability: the minimum is not unique and the match is rejected.
  double ambiguity_probability = 0.99;
  /// ...and whose scan stays further from the solution than this fraction of d: the RMS distance
  /// between the current scan's points placed by the restart's end and by the solution, over d
  /// (every point began d away). A restart that brings the points back most of the way returned
  /// to the same minimum; what is left is spIC's dependence on its start, which its covariance
  /// does not count and which is small against the match's covariance only where that is metres
  /// wide (docs/trajectory_slam.md, "Match validation at any scale"). 0: every end beyond the
  /// chi-square bound counts.
  double ambiguity_min_fraction = 0.25;
  /// Associations over the smaller scan's point count; below it the match is rejected (0: off).
  double min_overlap = 0.0;
  /// The covariance adds the initial-guess term (Brossard, Bonnabel and Barrau, "A New Approach
  /// to 3D ICP Covariance Estimation", RA-L 2020): spIC rerun from the guess moved by one
  /// standard deviation either way along each column of its covariance's Cholesky factor, the
  /// spread of the six results about the solution. spIC on sparse sonar points keeps part of its
  /// starting error, so a match shares some of the prediction's; the term says how much.
  bool initial_guess_term = false;
};

/// Why a match did not reach the filter; counted per run (metrics.json diagnostics).
enum class MatchRejection {
  kNone,
  kInvalid,     ///< spIC found too few associations or an ill-posed information matrix
  kLowOverlap,  ///< too few associations for the scans' size
  kAmbiguous,   ///< restarts from either side end at minima the covariance does not allow
  kInnovation,  ///< the filter's innovation gate: the match disagrees with the prediction
};
constexpr int kMatchRejectionReasons = 5;  ///< the values of MatchRejection, kNone included

/// "invalid", "low_overlap", "ambiguous", "innovation" (diagnostics key suffixes).
std::string rejection_name(MatchRejection rejection);

struct ValidatedMatch {
  ScanMatchResult match;
  MatchRejection rejection = MatchRejection::kNone;
  /// The observed directions of (x, y, yaw) as orthonormal rows: the identity, or 2 x 3 when the
  /// match does not observe a translation direction.
  Eigen::MatrixXd observed = Eigen::MatrixXd::Identity(3, 3);
  bool direction_dropped = false;  ///< observed has 2 rows
  int restarts = 0;                ///< spIC reruns: the restart test's and the initial-guess term's
};

/// spIC from the guess, then the validation above, then the initial-guess term.
ValidatedMatch match_and_validate(const std::vector<ScanPoint>& reference,
                                  const std::vector<ScanPoint>& current, const GaussianPose2& guess,
                                  const ScanMatchConfig& matching,
                                  const MatchValidationConfig& validation);

/// The innovation gate for d observed directions at the tail probability of the configured
/// 3-DOF gate (chi-square, 99 % by default): 3 DOF keeps the configured value.
double gate_for_dimensions(double gate_3dof, Eigen::Index d);

}  // namespace msislab
