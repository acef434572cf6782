// World-centric trajectory SLAM (Burguera et al. IROS 2010; the seed paper's Sec. III baseline):
// element i of the state is x_i = x^{i-1}_i, the pose of scan i in scan i-1's frame (x_0: scan 0
// in the start frame), a chain from the world forward. The pose of scan b in scan a's frame is
//   h(X) = x_{a+1} (+) ... (+) x_b,
// and scan i's world pose is start (+) x_0 (+) ... (+) x_i (docs/trajectory_slam.md).
#pragma once

#include "slam/trajectory_slam.hpp"

namespace msislab {

class WorldCentricSlam : public TrajectorySlam {
 public:
  using TrajectorySlam::TrajectorySlam;

  GaussianPose2 scan_pose_world(std::size_t i) const override;

 protected:
  std::vector<double> newest_scan_distances_m() const override;
  Pose2 relative_pose_of(const std::vector<Pose2>& elements, std::size_t a, std::size_t b,
                         Eigen::MatrixXd* H) const override;
  Pose2 pose_in_start_frame_of(const std::vector<Pose2>& elements, std::size_t b,
                               Eigen::MatrixXd* H) const override;
};

}  // namespace msislab
