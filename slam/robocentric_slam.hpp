// Robocentric trajectory SLAM (the seed paper's Sec. IV; docs/trajectory_slam.md). The state
// stores the trajectory from the current robot back to the world (paper Eq. 1):
//   element i = e_i = x^i_{i-1}, the pose of scan i-1 in scan i's frame (e_0: the start frame in
//   scan 0's), so that e_k (+) e_{k-1} (+) ... (+) e_0 is the world (start) frame seen from the
//   robot at scan k.
// Delayed inversion: the prediction appends the dead-reckoning motion as it comes,
// e_k = x^{k-1}_k (Eq. 2), so that this step's updates use the motion un-inverted; only after them
// is it inverted, e_k <- (-)e_k and P <- J P J^T with J = diag(I, J-) (Eq. 11-13). During the step
//   h(X) = (-)(e_{k-1} (+) ... (+) e_{j+1}) (+) e_k        (the pose of scan k in scan j, Eq. 5-8)
// and the world pose of scan i is start (+) (-)(e_i (+) ... (+) e_0).
#pragma once

#include "slam/trajectory_slam.hpp"

namespace msislab {

class RoboCentricSlam : public TrajectorySlam {
 public:
  using TrajectorySlam::TrajectorySlam;

  GaussianPose2 scan_pose_world(std::size_t i) const override;

  /// Whether the newest element is still the un-inverted motion (inside a step).
  bool newest_inverted() const { return newest_inverted_; }

 protected:
  void predict(const GaussianPose2& motion) override;
  void finish_step() override;
  std::vector<double> newest_scan_distances_m() const override;
  Pose2 relative_pose_of(const std::vector<Pose2>& elements, std::size_t a, std::size_t b,
                         Eigen::MatrixXd* H) const override;
  Pose2 pose_in_start_frame_of(const std::vector<Pose2>& elements, std::size_t b,
                               Eigen::MatrixXd* H) const override;

 private:
  /// The pose of scan b in the frame of scan first-1 (the start frame for first = 0) from
  /// elements first..b (of `elements`, the state's or a sample of it), with its Jacobian with
  /// respect to them (3 x 3(b - first + 1)).
  Pose2 chain_pose(const std::vector<Pose2>& elements, std::size_t first, std::size_t b,
                   Eigen::MatrixXd* H) const;
  bool is_raw(std::size_t i) const { return !newest_inverted_ && i + 1 == elements_.size(); }

  bool newest_inverted_ = true;
};

}  // namespace msislab
