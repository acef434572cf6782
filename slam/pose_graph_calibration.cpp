// The pose-graph SLAM's calibration (docs/pose_graph.md): the heading bias's scalar blocks (one per
// scan node, walking, or one constant) and the scale blocks (the sonar's range scale, the DVL's;
// one each), how they lead the belief's parameters, what a match observes through the range scale,
// the estimates read out, and the states the graph leaves to the filters. The scan step, with the
// odometry through the DVL's scale, is in pose_graph_slam.cpp.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "slam/pose_graph_slam.hpp"

namespace msislab {

std::vector<std::string> pose_graph_ignored_calibration(const CalibrationStatesConfig& c) {
  std::vector<std::string> out;
  if (c.compass_deviation) out.emplace_back("compass_deviation");
  return out;
}

bool PoseGraphSlam::estimates_heading_bias() const { return front_end_.calibration.heading_bias; }

bool PoseGraphSlam::estimates_range_scale() const { return front_end_.calibration.range_scale; }

bool PoseGraphSlam::estimates_dvl_scale() const { return front_end_.calibration.dvl_scale; }

std::vector<GraphConstant> PoseGraphSlam::estimated_constants() const {
  std::vector<GraphConstant> out;
  if (estimates_range_scale()) out.push_back(GraphConstant::kRangeScale);
  if (estimates_dvl_scale()) out.push_back(GraphConstant::kDvlScale);
  if (front_end_.calibration.clock_offset) out.push_back(GraphConstant::kClockOffset);
  return out;
}

Eigen::Index PoseGraphSlam::constant_at(GraphConstant which) const {
  const std::vector<GraphConstant> scales = estimated_constants();
  const auto it = std::find(scales.begin(), scales.end(), which);
  return static_cast<Eigen::Index>(estimates_heading_bias()) +
         static_cast<Eigen::Index>(it - scales.begin());
}

Eigen::VectorXd PoseGraphSlam::graph_parameters(std::optional<std::size_t> bias_of) const {
  const std::vector<GraphConstant> scales = estimated_constants();
  Eigen::VectorXd out(static_cast<Eigen::Index>(estimates_heading_bias()) +
                      static_cast<Eigen::Index>(scales.size()));
  if (estimates_heading_bias()) out(0) = bias_of ? graph_->heading_bias(bias_node(*bias_of)) : 0.0;
  for (const GraphConstant which : scales) out(constant_at(which)) = graph_->constant(which);
  return out;
}

GaussianPose2 PoseGraphSlam::predict_match(const PoseGraphBelief& belief, Eigen::Index c,
                                           Eigen::MatrixXd* H) const {
  GaussianPose2 h = belief.predict(c, H);
  const bool clock = front_end_.calibration.clock_offset;
  if (!estimates_range_scale() && !clock) return h;
  if (clock) {
    // The scans show the frames at t + tau (the filters' model): h_tau = (-)(tau u_a) (+) h (+)
    // (tau u_b), dh_tau/dh = J1 J2', dh_tau/dtau = J1 J1' J- u_a + J2 u_b.
    const Eigen::Index t = constant_at(GraphConstant::kClockOffset);
    const double tau = belief.parameters(t);
    const Eigen::Vector3d& u_a = velocities_.at(belief.nodes.at(static_cast<std::size_t>(c)) - 1);
    const Eigen::Vector3d& u_b =
        velocities_.at(belief.nodes.at(static_cast<std::size_t>(belief.newest)) - 1);
    Eigen::Matrix3d J_inverse, J1_inner, J2_inner, J1, J2;
    const Pose2 back = Pose2(Eigen::Vector3d(tau * u_a)).inverse(&J_inverse);
    const Pose2 inner = back.compose(h.mean, &J1_inner, &J2_inner);
    h.mean = inner.compose(Pose2(Eigen::Vector3d(tau * u_b)), &J1, &J2);
    *H = J1 * J2_inner * *H;
    H->col(t) = J1 * J1_inner * J_inverse * u_a + J2 * u_b;
  }
  if (estimates_range_scale()) {
    // A match sees the scans' geometry s times the true one (the filters' model): h_s = (s t,
    // yaw), dh_s/ds = (t, 0), dh_s/d(the rest) = diag(s, s, 1) dh/d(the rest).
    const Eigen::Index r = constant_at(GraphConstant::kRangeScale);
    const double s = belief.parameters(r);
    H->topRows<2>() *= s;
    H->block<2, 1>(0, r) = h.mean.translation();
    h.mean = Pose2(s * h.mean.x(), s * h.mean.y(), h.mean.yaw());
  }
  const Eigen::MatrixXd P = *H * belief.cov * H->transpose();
  h.cov = 0.5 * (P + P.transpose());
  return h;
}

std::size_t PoseGraphSlam::bias_node(std::size_t node) const {
  // A bias that does not walk is one constant: the first scan's block.
  return front_end_.calibration.heading_bias_walk_deg_per_sqrt_s > 0.0 ? node : 1;
}

void PoseGraphSlam::add_bias_block(std::size_t node, double t_s, PoseGraphBelief& belief) {
  const CalibrationStatesConfig& c = front_end_.calibration;
  const double walk_rad = c.heading_bias_walk_deg_per_sqrt_s * M_PI / 180.0;
  if (node == 1) {
    const double sigma_rad = c.heading_bias_sigma_deg * M_PI / 180.0;
    graph_->add_heading_bias(1, belief.parameters(0), !(sigma_rad > 0.0));
    if (sigma_rad > 0.0) graph_->add_heading_bias_prior(1, 0.0, sigma_rad);
  } else if (walk_rad > 0.0) {
    const double dt_s = std::max(0.0, t_s - previous_t_s_);
    // The walk over the scans' interval (paper-free: the filters' model, docs/pose_graph.md).
    belief.cov(0, 0) += walk_rad * walk_rad * dt_s;
    graph_->add_heading_bias(node, belief.parameters(0), false);
    if (dt_s > 0.0) {
      graph_->add_heading_bias_walk(node - 1, node, walk_rad * std::sqrt(dt_s));
    } else {
      graph_->add_heading_bias_walk(node - 1, node, 1e-9);  // the same instant: the same bias
    }
  }
  previous_t_s_ = t_s;
}

std::vector<CalibrationEstimate> PoseGraphSlam::calibration() const {
  std::vector<CalibrationEstimate> out;
  if (motions_.empty()) return out;
  // The filters' order (TrajectorySlam::calibration): the range scale, the DVL scale, the bias.
  // A scale after the smoothing solve (scan_pose_world): the smoothed graph's; before, online.
  for (const GraphConstant which : estimated_constants()) {
    const std::size_t i = static_cast<std::size_t>(which);
    const auto& [value, sd] = smoothed_.empty() ? constant_estimates_[i] : smoothed_constants_[i];
    constexpr const char* kNames[] = {"range_scale", "dvl_scale", "clock_offset_s"};
    out.push_back({kNames[i], value, sd});
  }
  if (estimates_heading_bias()) {
    out.push_back({"heading_bias_deg", bias_.first * 180.0 / M_PI, bias_.second * 180.0 / M_PI});
  }
  return out;
}

}  // namespace msislab
