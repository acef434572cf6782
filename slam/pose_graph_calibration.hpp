// The pose-graph SLAM's calibration layout (docs/pose_graph.md): which calibration the graph
// estimates (trajectory_slam.calibration), where each leads the belief's parameters (the heading
// bias first, then the constants in GraphConstant order: the sonar's range scale, the DVL's, the
// sonar clock's offset, the compass deviation's a and b), their values as the graph holds them,
// and the odometry appended to a belief through the DVL's scale and the deviation. Shared by the
// scan step (slam/pose_graph_slam.hpp) and the two online beliefs (slam/pose_graph_online.hpp).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/calibration_model.hpp"
#include "slam/calibration_states_config.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_belief.hpp"

namespace msislab {

class PoseGraphCalibration {
 public:
  /// graph: the pose graph whose blocks hold the values (it must outlive this); start_cov: node
  /// 0's covariance (zero when it is held fixed: its heading then carries no deviation).
  PoseGraphCalibration(const CalibrationStatesConfig& config, const PoseGraph& graph,
                       const Eigen::Matrix3d& start_cov)
      : config_(config), graph_(&graph), start_cov_(start_cov) {}

  const CalibrationStatesConfig& config() const { return config_; }
  bool estimates_heading_bias() const { return config_.heading_bias; }
  bool estimates_range_scale() const { return config_.range_scale; }
  bool estimates_dvl_scale() const { return config_.dvl_scale; }
  /// The graph's constants switched on, in GraphConstant order (the range scale, the DVL's, the
  /// clock offset, the deviation's a and b).
  std::vector<GraphConstant> estimated_constants() const;
  /// A constant's index in the belief's parameters (after the heading bias, in that order).
  Eigen::Index constant_at(GraphConstant which) const;
  /// The belief's parameters as the graph holds them: the heading bias of node bias_of's block
  /// (none: 0, before the first scan's), the constants.
  Eigen::VectorXd graph_parameters(std::optional<std::size_t> bias_of) const;
  /// The node whose bias block scan node `node` reads the compass through: its own when the bias
  /// walks, else the first scan's (a constant).
  std::size_t bias_node(std::size_t node) const;

  /// The odometry goes through the calibration (the DVL's scale or the deviation estimated).
  bool calibrates_odometry() const;
  /// The DVL scale's and the deviation's a's index in the belief's parameters; -1: not estimated.
  Eigen::Index odometry_k_at() const;
  Eigen::Index odometry_ab_at() const;
  /// Whether the motion to scan node `node` starts from a heading the compass's deviation is in:
  /// always but from an exact start (node 0 held fixed).
  bool start_deviated(std::size_t node) const;
  /// The true motion to node node_to behind a measured one (slam/calibration_model.hpp), at the
  /// calibration `parameters` (the belief's) and the motion's two headings.
  CalibratedMotion calibrated_step(const Eigen::VectorXd& parameters, const Pose2& motion,
                                   double psi_from_rad, double psi_to_rad,
                                   std::size_t node_to) const;
  /// The odometry edge in the belief (Eq. 2): node `node` appended as the previous one composed
  /// with the motion, through the DVL's scale and the compass's deviation when estimated; it
  /// becomes the newest.
  void append_odometry(PoseGraphBelief& belief, std::size_t node, Eigen::Index previous,
                       const GaussianPose2& motion) const;

 private:
  CalibrationStatesConfig config_;
  const PoseGraph* graph_;
  Eigen::Matrix3d start_cov_;
};

}  // namespace msislab
