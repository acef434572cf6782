// Scan registration errors in trajectory SLAM (docs/trajectory_slam.md, "Scan registration
// errors"): a scan's own errors enter every match of that scan. Counted once per match, they make a
// filter overconfident where several scans match one, and underconfident along a chain of
// consecutive matches, where a scan's error enters one match as the current scan and the next as
// the reference with the opposite sign. With the option on, the state holds them:
// - each half-scan's motion error xi ~ N(0, I) (ScanPoint::distortion), which spIC's loadings M
//   carry into each match exactly (to first order);
// - each scan's rigid registration error e_s for its points' reading noise, as if the points sat
//   displaced by e_s in the scan's frame, its prior that part of the scan's share of its first
//   match, moved into its frame.
// A match of scan b against scan a then observes
//   z = (-)e_a (+) h(X) (+) e_b + sum M_a,side xi_a,side + sum M_b,side xi_b,side + w,
// w ~ N(0, R), R the match's own part: its covariance less both scans' shares, plus any part of a
// points' share that e_s's prior does not cover.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "slam/trajectory_slam.hpp"

namespace msislab {

namespace {

/// The PSD part of a symmetric matrix: its negative eigenvalues set to zero.
Eigen::Matrix3d positive_part(const Eigen::Matrix3d& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (A + A.transpose()));
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
         eigen.eigenvectors().transpose();
}

/// J^-1 C J^-T: a covariance of dz = J e moved onto e.
Eigen::Matrix3d moved_onto(const Eigen::Matrix3d& J, const Eigen::Matrix3d& C) {
  const Eigen::Matrix3d J_inverse = J.inverse();
  return J_inverse * C * J_inverse.transpose();
}

}  // namespace

Eigen::Index TrajectorySlam::add_shared_error(const Eigen::Matrix3d& cov) {
  // [P_cc, P_cx; P_xc, P_xx] -> [P_cc, 0, P_cx; 0, cov, 0; P_xc, 0, P_xx]: the new rows after the
  // calibration, before the elements.
  const Eigen::Index c = calibration_.size();
  const Eigen::Index x = P_.rows() - c;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(P_.rows() + 3, P_.cols() + 3);
  P.topLeftCorner(c, c) = P_.topLeftCorner(c, c);
  P.topRightCorner(c, x) = P_.topRightCorner(c, x);
  P.bottomLeftCorner(x, c) = P_.bottomLeftCorner(x, c);
  P.bottomRightCorner(x, x) = P_.bottomRightCorner(x, x);
  P.block<3, 3>(c, c) = cov;
  P_ = std::move(P);
  calibration_.conservativeResize(c + 3);
  calibration_.tail<3>().setZero();
  return c;
}

TrajectorySlam::ScanErrors& TrajectorySlam::scan_errors(std::size_t s) {
  if (scan_errors_.size() <= s) scan_errors_.resize(s + 1);
  return scan_errors_[s];
}

Eigen::Matrix3d TrajectorySlam::match_noise(
    std::size_t j, std::size_t k, const ScanMatchResult& match,
    std::vector<RelativePoseObservation::SharedError>* shared) {
  const ScanSharedErrors held = config_.filter.scan_shared_errors;
  if (held == ScanSharedErrors::kNone) return match.estimate.cov;
  // The half-scans' motion errors, loaded exactly; what is left of each scan's share is its
  // points'.
  Eigen::Matrix3d points_k = match.current_share, points_j = match.reference_share;
  const auto share_half = [&](std::size_t s, int side, const Eigen::Matrix3d& M,
                              Eigen::Matrix3d& points) {
    if (M.isZero(0.0)) return;
    Eigen::Index& row = scan_errors(s).half_row[static_cast<std::size_t>(side)];
    if (row < 0) row = add_shared_error(Eigen::Matrix3d::Identity());
    if (shared) shared->push_back({row, M});
    points -= M * M.transpose();
  };
  for (int side = 0; side < 2; ++side) {
    share_half(k, side, match.current_loading.half[static_cast<std::size_t>(side)], points_k);
    share_half(j, side, match.reference_half[static_cast<std::size_t>(side)], points_j);
  }
  if (held == ScanSharedErrors::kMotion) {
    const Eigen::Matrix3d own =
        match.estimate.cov - match.current_share - match.reference_share + points_k + points_j;
    return 0.5 * (own + own.transpose());
  }
  // The points' rigid errors: dz = J_k e_k + J_j e_j at e = 0, J_k = d(z (+) e)/de and
  // J_j = d((-)e (+) z)/de.
  const Pose2& z = match.estimate.mean;
  Eigen::Matrix3d J_z, J_k, J_inverse_e, J_u;
  z.compose(Pose2(), &J_z, &J_k);
  Pose2().inverse(&J_inverse_e).compose(z, &J_u, &J_z);
  const Eigen::Matrix3d J_j = J_u * J_inverse_e;
  const auto uncovered = [&](std::size_t s, const Eigen::Matrix3d& J,
                             const Eigen::Matrix3d& points) -> Eigen::Matrix3d {
    ScanErrors& errors = scan_errors(s);
    if (errors.rigid_row < 0) {
      errors.rigid_prior = moved_onto(J, points);
      errors.rigid_row = add_shared_error(errors.rigid_prior);
    }
    return positive_part(points - J * errors.rigid_prior * J.transpose());
  };
  const Eigen::Matrix3d own = match.estimate.cov - match.current_share - match.reference_share +
                              uncovered(k, J_k, points_k) + uncovered(j, J_j, points_j);
  return 0.5 * (own + own.transpose());
}

Pose2 TrajectorySlam::with_scan_errors(const Pose2& h, std::size_t a, std::size_t b,
                                       Eigen::MatrixXd* H) const {
  const auto row = [&](std::size_t s) -> Eigen::Index {
    return s < scan_errors_.size() ? scan_errors_[s].rigid_row : -1;
  };
  const Eigen::Index row_a = row(a), row_b = row(b);
  if (row_a < 0 && row_b < 0) return h;
  const Pose2 e_a = row_a >= 0 ? Pose2(Eigen::Vector3d(calibration_.segment<3>(row_a))) : Pose2();
  const Pose2 e_b = row_b >= 0 ? Pose2(Eigen::Vector3d(calibration_.segment<3>(row_b))) : Pose2();
  Eigen::Matrix3d J_inverse, J_u, J_h, J_v, J_e;
  const Pose2 v = e_a.inverse(&J_inverse).compose(h, &J_u, &J_h);
  const Pose2 z = v.compose(e_b, &J_v, &J_e);
  if (H) {
    *H = J_v * J_h * *H;
    if (row_a >= 0) H->middleCols<3>(row_a) += J_v * J_u * J_inverse;
    if (row_b >= 0) H->middleCols<3>(row_b) += J_e;
  }
  return z;
}

}  // namespace msislab
