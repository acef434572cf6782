// The observation model of trajectory SLAM (paper Eq. 5-8) and the calibration that enters it:
// the prediction a match starts from, h(X) of a match with the range scale, the stacked residual
// of a step's matches and its NIS. The updates they make (update_relative_poses, update_compass,
// through the windowed iterated update) and the step are in trajectory_slam.cpp.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "slam/trajectory_slam.hpp"

namespace msislab {

namespace {

/// The rows of P for the calibration (the first c) and the elements from row f on, m of them.
std::vector<Eigen::Index> calibration_and_rows(Eigen::Index c, Eigen::Index f, Eigen::Index m) {
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < c; ++i) rows.push_back(i);
  for (Eigen::Index i = 0; i < m; ++i) rows.push_back(f + i);
  return rows;
}

}  // namespace

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
  if (deviation_row_ >= 0) {
    constexpr double kRadToDeg = 180.0 / M_PI;
    const Eigen::Index r = deviation_row_;
    out.push_back({"compass_deviation_cos_deg", calibration_(r) * kRadToDeg,
                   std::sqrt(P_(r, r)) * kRadToDeg});
    out.push_back({"compass_deviation_sin_deg", calibration_(r + 1) * kRadToDeg,
                   std::sqrt(P_(r + 1, r + 1)) * kRadToDeg});
  }
  return out;
}

ValidatedMatch TrajectorySlam::match(std::size_t j, std::size_t k, GaussianPose2& predicted) const {
  Eigen::MatrixXd H;
  predicted.mean = observed_relative_pose(j, k, &H);
  const Eigen::Index c = calibration_.size();
  if (c == 0) {
    predicted.cov = propagate(j + 1, H);
  } else {
    const std::vector<Eigen::Index> rows =
        calibration_and_rows(c, element_row(j + 1), H.cols() - c);
    predicted.cov = H * P_(rows, rows) * H.transpose();
  }
  return match_and_validate(points_[j], points_[k], predicted, config_.matching,
                            config_.validation);
}

Pose2 TrajectorySlam::observed_relative_pose(std::size_t a, std::size_t b,
                                             Eigen::MatrixXd* H) const {
  Eigen::MatrixXd H_pose;
  const Pose2 h = relative_pose(a, b, H ? &H_pose : nullptr);
  const Eigen::Index c = calibration_.size();
  if (range_scale_row_ < 0) {
    if (H) {
      H->setZero(3, c + H_pose.cols());
      H->rightCols(H_pose.cols()) = H_pose;
    }
    return h;
  }
  // A match sees the scans' geometry s times the true one: h_s = (s t, yaw), so
  // dh_s/ds = (t, 0) and dh_s/dX = diag(s, s, 1) dh/dX.
  const double s = calibration_(range_scale_row_);
  if (H) {
    H->setZero(3, c + H_pose.cols());
    H->block<2, 1>(0, range_scale_row_) = h.translation();
    H->rightCols(H_pose.cols()) = H_pose;
    H->rightCols(H_pose.cols()).topRows<2>() *= s;
  }
  return Pose2(s * h.x(), s * h.y(), h.yaw());
}

Eigen::VectorXd TrajectorySlam::stacked_residual(std::size_t b,
                                                 const std::vector<RelativePoseObservation>& z,
                                                 Eigen::MatrixXd* H) const {
  const std::size_t first = first_involved(b, z);
  const Eigen::Index c = calibration_.size();
  Eigen::Index rows = 0;
  for (const RelativePoseObservation& o : z) rows += o.observed.rows();
  Eigen::VectorXd r(rows);
  if (H) H->setZero(rows, c + static_cast<Eigen::Index>(3 * (b + 1 - first)));
  Eigen::Index row = 0;
  for (const RelativePoseObservation& o : z) {
    // z observes h(X) = the pose of scan b in scan a (Eq. 5-8), in the directions A = observed:
    // A (z - h(X)) with Jacobian A H on the calibration and the elements a+1..b.
    Eigen::MatrixXd H_o;
    const Eigen::Vector3d r_o =
        pose_difference(o.z, observed_relative_pose(o.reference, b, H ? &H_o : nullptr));
    const Eigen::Index d = o.observed.rows();
    r.segment(row, d) = o.observed * r_o;
    if (H) {
      const Eigen::Index n = H_o.cols() - c;
      H->block(row, 0, d, c) = o.observed * H_o.leftCols(c);
      H->block(row, c + static_cast<Eigen::Index>(3 * (o.reference + 1 - first)), d, n) =
          o.observed * H_o.rightCols(n);
    }
    row += d;
  }
  return r;
}

double TrajectorySlam::innovation_nis(std::size_t b, const std::vector<RelativePoseObservation>& z,
                                      const Eigen::MatrixXd& R) const {
  Eigen::MatrixXd H;
  const Eigen::VectorXd r = stacked_residual(b, z, &H);
  const Eigen::Index c = calibration_.size();
  const Eigen::Index first = element_row(first_involved(b, z));
  Eigen::MatrixXd S;
  if (c == 0) {
    S = H * P_.block(first, first, H.cols(), H.cols()) * H.transpose() + R;
  } else {
    const std::vector<Eigen::Index> rows = calibration_and_rows(c, first, H.cols() - c);
    S = H * P_(rows, rows) * H.transpose() + R;
  }
  return r.dot(S.ldlt().solve(r));
}

}  // namespace msislab
