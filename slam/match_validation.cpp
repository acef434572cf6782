#include "slam/match_validation.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "slam/line_normals.hpp"
#include "stats/chi_square.hpp"

namespace msislab {

std::string rejection_name(MatchRejection rejection) {
  switch (rejection) {
    case MatchRejection::kNone:
      return "none";
    case MatchRejection::kInvalid:
      return "invalid";
    case MatchRejection::kLowOverlap:
      return "low_overlap";
    case MatchRejection::kAmbiguous:
      return "ambiguous";
    case MatchRejection::kInnovation:
      return "innovation";
  }
  return "none";
}

namespace {

/// The frame (u, v, yaw) in which the restarts are compared, as rows. u: the translation
/// direction the reference's walls constrain least (the normals' scatter sum n n^T is smallest
/// along a corridor's axis); v across it. With too few wall-like points to tell (from_walls
/// false), u and v are the axes of the match's covariance and both are tested.
struct ComparisonFrame {
  Eigen::Matrix3d rows = Eigen::Matrix3d::Zero();
  bool from_walls = false;
};

ComparisonFrame comparison_frame(const std::vector<ScanPoint>& reference, const GaussianPose2& q,
                                 const ScanMatchConfig& matching) {
  Eigen::Matrix2d normal_scatter = Eigen::Matrix2d::Zero();
  int walls = 0;
  for (const Eigen::Vector2d& n : line_normals(reference, matching.line)) {
    if (n.squaredNorm() > 0.0) normal_scatter += n * n.transpose(), ++walls;
  }
  ComparisonFrame frame;
  frame.from_walls = walls >= matching.min_inliers;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(
      frame.from_walls ? normal_scatter : Eigen::Matrix2d(q.cov.topLeftCorner<2, 2>()));
  const Eigen::Vector2d u = eigen.eigenvectors().col(frame.from_walls ? 0 : 1);
  frame.rows.block<1, 2>(0, 0) = u.transpose();
  frame.rows.block<1, 2>(1, 0) = Eigen::Vector2d(-u.y(), u.x()).transpose();
  frame.rows(2, 2) = 1.0;
  return frame;
}

/// Where the restarts from either side of the solution q ended, and along which axes of the
/// frame some restart slid away from it.
struct RestartEnds {
  std::vector<Eigen::Vector3d> ends;  ///< each valid restart's end against q, in the frame
  /// Per end: the RMS distance between the current points placed by the end and by q, over d.
  std::vector<double> remaining_fraction;
  bool slid[2] = {false, false};
};

/// The RMS distance (m) between the current scan's points placed in the reference frame by a and
/// by b.
double rms_point_distance_m(const std::vector<ScanPoint>& current, const Pose2& a, const Pose2& b) {
  if (current.empty()) return 0.0;
  const Eigen::Matrix2d dR = a.rotation() - b.rotation();
  const Eigen::Vector2d dt = a.translation() - b.translation();
  double sum_m2 = 0.0;
  for (const ScanPoint& point : current) sum_m2 += (dR * point.p_m + dt).squaredNorm();
  return std::sqrt(sum_m2 / static_cast<double>(current.size()));
}

/// Restarts spIC from q moved along the frame's tested axes, C being q's covariance in the
/// frame; counts them in `restarts`.
RestartEnds restart_ends(const std::vector<ScanPoint>& reference,
                         const std::vector<ScanPoint>& current, const GaussianPose2& guess,
                         const GaussianPose2& q, const ComparisonFrame& frame,
                         const Eigen::Matrix3d& C, const ScanMatchConfig& matching,
                         const MatchValidationConfig& validation, int& restarts) {
  RestartEnds out;
  for (int axis = 0; axis < (frame.from_walls ? 1 : 2); ++axis) {
    const double offset_m = std::max(validation.restart_offset_m, 3.0 * std::sqrt(C(axis, axis)));
    for (const double side : {1.0, -1.0}) {
      // From the solution moved by the offset, the guess's covariance widened along the axis so
      // the offset is two standard deviations there: the association gate reaches the true
      // counterparts from the restart.
      const Eigen::Vector3d step = offset_m * frame.rows.row(axis).transpose();
      GaussianPose2 start = guess;
      start.mean = Pose2(q.mean.vector() + side * step);
      start.cov += 0.25 * step * step.transpose();
      const ScanMatchResult restart = match_scans(reference, current, start, matching);
      ++restarts;
      if (!restart.valid) continue;  // no minimum from there: no evidence either way
      const Eigen::Vector3d d = frame.rows * pose_difference(restart.estimate.mean, q.mean);
      if (std::abs(d(axis)) > validation.max_kept_fraction * offset_m) out.slid[axis] = true;
      out.ends.push_back(d);
      out.remaining_fraction.push_back(
          rms_point_distance_m(current, restart.estimate.mean, q.mean) / offset_m);
    }
  }
  return out;
}

/// Whether every restart ends where the solution is in the kept directions: within the gate of
/// the solution's covariance there (C_kept, factored), or with the scan brought back to within
/// min_fraction of the offset (the same minimum, reached from another start).
bool restarts_agree(const RestartEnds& restarts, const std::vector<Eigen::Index>& kept,
                    const Eigen::LDLT<Eigen::MatrixXd>& C_kept, double gate, double min_fraction) {
  for (std::size_t i = 0; i < restarts.ends.size(); ++i) {
    const Eigen::VectorXd d = restarts.ends[i](kept);
    if (d.dot(C_kept.solve(d)) > gate && restarts.remaining_fraction[i] > min_fraction) {
      return false;
    }
  }
  return true;
}

/// The restart test (the header's): false when it rejects the match as ambiguous; drops an
/// unobserved direction from out.observed.
bool passes_restarts(const std::vector<ScanPoint>& reference, const std::vector<ScanPoint>& current,
                     const GaussianPose2& guess, const ScanMatchConfig& matching,
                     const MatchValidationConfig& validation, ValidatedMatch& out) {
  const GaussianPose2& q = out.match.estimate;
  const ComparisonFrame frame = comparison_frame(reference, q, matching);
  // Each restart's end against the solution, in the frame.
  const Eigen::Matrix3d C = frame.rows * q.cov * frame.rows.transpose();
  const RestartEnds restarts =
      restart_ends(reference, current, guess, q, frame, C, matching, validation, out.restarts);
  // The directions observed: yaw, and each axis no restart slid along.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index axis = 0; axis < 2; ++axis) {
    if (!restarts.slid[axis]) kept.push_back(axis);
  }
  kept.push_back(2);
  // In those directions every restart must end where the solution is.
  const double gate =
      chi2_quantile(validation.ambiguity_probability, static_cast<double>(kept.size()));
  const Eigen::LDLT<Eigen::MatrixXd> C_kept(C(kept, kept));
  if (!restarts_agree(restarts, kept, C_kept, gate, validation.ambiguity_min_fraction)) {
    out.rejection = MatchRejection::kAmbiguous;
    return false;
  }
  if (kept.size() < 3) {
    out.observed = frame.rows(kept, Eigen::all);
    out.direction_dropped = true;
  }
  return true;
}

/// The initial-guess term of a match solved from guess: the covariance, about the solution, of
/// spIC's results from the guess's six sigma points (L L^T = the guess's covariance, one standard
/// deviation either way along each column of L). A rerun that fails counts as the solution.
Eigen::Matrix3d initial_guess_covariance(const std::vector<ScanPoint>& reference,
                                         const std::vector<ScanPoint>& current,
                                         const GaussianPose2& guess, const Pose2& solution,
                                         const ScanMatchConfig& matching, int& runs) {
  const Eigen::LLT<Eigen::Matrix3d> llt(guess.cov);
  if (llt.info() != Eigen::Success) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d L = llt.matrixL();
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (Eigen::Index c = 0; c < 3; ++c) {
    for (const double side : {-1.0, 1.0}) {
      GaussianPose2 start = guess;
      start.mean = Pose2(Eigen::Vector3d(guess.mean.vector() + side * L.col(c)));
      const ScanMatchResult rerun = match_scans(reference, current, start, matching);
      ++runs;
      const Eigen::Vector3d d =
          rerun.valid ? pose_difference(rerun.estimate.mean, solution) : Eigen::Vector3d::Zero();
      spread += d * d.transpose();
    }
  }
  // The unscented transform with n + kappa = 1: weights 1/2, the centre (the solution) adding
  // nothing about itself.
  return 0.5 * spread;
}

}  // namespace

ValidatedMatch match_and_validate(const std::vector<ScanPoint>& reference,
                                  const std::vector<ScanPoint>& current, const GaussianPose2& guess,
                                  const ScanMatchConfig& matching,
                                  const MatchValidationConfig& validation) {
  ValidatedMatch out;
  out.match = match_scans(reference, current, guess, matching);
  if (!out.match.valid) {
    out.rejection = MatchRejection::kInvalid;
    return out;
  }
  const double smaller = static_cast<double>(std::min(reference.size(), current.size()));
  if (validation.min_overlap > 0.0 && out.match.inliers < validation.min_overlap * smaller) {
    out.rejection = MatchRejection::kLowOverlap;
    return out;
  }
  if (validation.restart_offset_m > 0.0 &&
      !passes_restarts(reference, current, guess, matching, validation, out)) {
    return out;
  }
  if (validation.initial_guess_term) {
    out.match.estimate.cov += initial_guess_covariance(
        reference, current, guess, out.match.estimate.mean, matching, out.restarts);
  }
  return out;
}

double gate_for_dimensions(double gate_3dof, Eigen::Index d) {
  if (d == 3) return gate_3dof;
  return chi2_quantile(1.0 - chi2_survival(gate_3dof, 3), static_cast<double>(d));
}

}  // namespace msislab
