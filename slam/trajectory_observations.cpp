// The observation model of trajectory SLAM (paper Eq. 5-8) and the calibration that enters it:
// the prediction a match starts from, h(X) of a match with the range scale and the clock offset,
// the stacked residual of a step's matches and its NIS. The updates they make
// (update_relative_poses, update_compass, through the windowed iterated update) and the step are in
// trajectory_slam.cpp.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "slam/calibration_model.hpp"
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
  return match_and_validate(points_[j], points_[k], predicted, config_.front_end.matching,
                            config_.front_end.validation);
}

Pose2 TrajectorySlam::observed_relative_pose_of(const std::vector<Pose2>& elements, std::size_t a,
                                                std::size_t b, Eigen::MatrixXd* H) const {
  Eigen::MatrixXd H_pose;
  Pose2 h = relative_pose_of(elements, a, b, H ? &H_pose : nullptr);
  const Eigen::Index c = calibration_.size();
  if (H) {
    H->setZero(3, c + H_pose.cols());
    H->rightCols(H_pose.cols()) = H_pose;
  }
  if (clock_row_ >= 0) {
    // The scans show the frames at t + tau (slam/calibration_model.hpp): z = (-)(tau u_a) (+) h
    // (+) (tau u_b), so dz/dX = (dh_tau/dh) dh/dX.
    const ClockShifted shifted = clock_shifted(h, calibration_(clock_row_), velocities_.at(a),
                                               velocities_.at(b));  // one per scan (add_scan)
    h = shifted.h;
    if (H) {
      H->col(clock_row_) = shifted.d_tau;
      H->rightCols(H_pose.cols()) = shifted.d_h * H_pose;
    }
  }
  if (range_scale_row_ >= 0) {
    // A match sees the scans' geometry s times the true one: h_s = (s t, yaw), so
    // dh_s/ds = (t, 0) and dh_s/d(the rest) = diag(s, s, 1) dh/d(the rest).
    const double s = calibration_(range_scale_row_);
    if (H) {
      H->topRows<2>() *= s;
      H->block<2, 1>(0, range_scale_row_) = h.translation();
    }
    h = Pose2(s * h.x(), s * h.y(), h.yaw());
  }
  return with_scan_errors(h, a, b, H);  // slam/scan_registration_errors.cpp
}

Eigen::VectorXd TrajectorySlam::stacked_residual(const std::vector<Pose2>& elements, std::size_t b,
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
    Pose2 h = observed_relative_pose_of(elements, o.reference, b, H ? &H_o : nullptr);
    if (!o.shared.empty()) {
      // z = h(X) + sum loading x_row (the errors it shares with other matches, in the state).
      Eigen::Vector3d v = h.vector();
      for (const RelativePoseObservation::SharedError& e : o.shared) {
        v += e.loading * calibration_.segment<3>(e.row);
        if (H) H_o.middleCols<3>(e.row) += e.loading;
      }
      h = Pose2(v);
    }
    const Eigen::Vector3d r_o = pose_difference(o.z, h);
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
  const Eigen::VectorXd r = stacked_residual(elements_, b, z, &H);
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
