// World-centric trajectory SLAM (Burguera et al. IROS 2010; the seed paper's Sec. III baseline):
// the state is the chain of relative motions between consecutive scans from the start pose,
// X = [x_1; ...; x_n] (x_1 from the start), with its full covariance. Each new scan:
//   predict:   X <- [X; x_n], P <- diag(P, P_n)      (the dead-reckoning motion, paper Eq. 2
//   analog) associate: past scans whose estimated centre lies within gamma of the new one observe:
//   z = spIC(scan_j, scan_n) ~ h(X) = x_{j+1} (+) ... (+) x_n   (pose_chain) update:    iterated
//   EKF on z (paper Eq. 9-10), gated on the innovation's NIS.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "slam/gaussian_pose.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_matching.hpp"

namespace msislab {

struct TrajectorySlamConfig {
  double association_distance_m = 10.0;  ///< gamma: match past scans closer than this (m)
  int max_matches_per_scan = 3;          ///< the nearest candidates first
  int iekf_iterations = 5;               ///< relinearisations of the update (1 = plain EKF)
  double innovation_gate_chi2 = 11.34;   ///< 3 DOF, 99%: inconsistent matches are rejected
  ScanMatchConfig matching;
};

struct SlamStepStats {
  int candidates = 0;
  int matched = 0;   ///< spIC valid
  int accepted = 0;  ///< passed the innovation gate and updated the state
};

class WorldCentricSlam {
 public:
  WorldCentricSlam(const TrajectorySlamConfig& config, const GaussianPose2& start_world);

  /// Adds a scan (its points in its own frame and its motion from the previous scan's frame) and
  /// closes the loops it finds.
  SlamStepStats add_scan(const Scan& scan);

  std::size_t scans() const { return motions_.size(); }
  /// The world pose of scan i with its covariance.
  GaussianPose2 scan_pose_world(std::size_t i) const;
  /// The relative motions (the state) and their covariance.
  const std::vector<Pose2>& motions() const { return motions_; }
  const Eigen::MatrixXd& covariance() const { return P_; }

  /// h(X) for scans a < b: the pose of scan b in scan a's frame, and its Jacobian with respect to
  /// the whole state (3 x 3n).
  Pose2 relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const;

 private:
  bool update(std::size_t a, std::size_t b, const GaussianPose2& z);

  TrajectorySlamConfig config_;
  GaussianPose2 start_world_;
  std::vector<Pose2> motions_;
  Eigen::MatrixXd P_;
  std::vector<std::vector<ScanPoint>> points_;
};

}  // namespace msislab
