// The pose-graph SLAM's calibration (docs/pose_graph.md): the heading bias's scalar blocks (one per
// scan node, walking, or one constant) and the constants' blocks (the sonar's range scale, the
// DVL's, the sonar clock's offset, the compass deviation's a and b; one each), how they lead the
// belief's parameters and the odometry appended to the belief through the DVL's scale and the
// deviation (PoseGraphCalibration), what a match observes through the range scale and the clock,
// and the estimates read out. The scan step, with the compass through the bias and the deviation,
// is in pose_graph_slam.cpp.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/angles.hpp"
#include "slam/calibration_model.hpp"
#include "slam/pose_graph_calibration.hpp"
#include "slam/pose_graph_slam.hpp"

namespace msislab {

std::vector<GraphConstant> PoseGraphCalibration::estimated_constants() const {
  std::vector<GraphConstant> out;
  if (estimates_range_scale()) out.push_back(GraphConstant::kRangeScale);
  if (estimates_dvl_scale()) out.push_back(GraphConstant::kDvlScale);
  if (config_.clock_offset) out.push_back(GraphConstant::kClockOffset);
  if (config_.compass_deviation) {
    out.push_back(GraphConstant::kDeviationCos);
    out.push_back(GraphConstant::kDeviationSin);
  }
  return out;
}

Eigen::Index PoseGraphCalibration::constant_at(GraphConstant which) const {
  const std::vector<GraphConstant> scales = estimated_constants();
  const auto it = std::find(scales.begin(), scales.end(), which);
  return static_cast<Eigen::Index>(estimates_heading_bias()) +
         static_cast<Eigen::Index>(it - scales.begin());
}

Eigen::VectorXd PoseGraphCalibration::graph_parameters(std::optional<std::size_t> bias_of) const {
  const std::vector<GraphConstant> scales = estimated_constants();
  Eigen::VectorXd out(static_cast<Eigen::Index>(estimates_heading_bias()) +
                      static_cast<Eigen::Index>(scales.size()));
  if (estimates_heading_bias()) out(0) = bias_of ? graph_->heading_bias(bias_node(*bias_of)) : 0.0;
  for (const GraphConstant which : scales) out(constant_at(which)) = graph_->constant(which);
  return out;
}

void PoseGraphCalibration::append_odometry(PoseGraphBelief& belief, std::size_t node,
                                           Eigen::Index previous,
                                           const GaussianPose2& motion) const {
  if (!calibrates_odometry()) {
    belief.append_composed(node, previous, motion);
    return;
  }
  // The new node's heading: the previous one's turned by the true motion, whose heading change
  // depends on it through the deviation (one fixed-point step from the measured one).
  const double psi_0 = belief.means[static_cast<std::size_t>(previous)].yaw();
  const double psi_guess = psi_0 + calibrated_step(belief.parameters, motion.mean, psi_0,
                                                   psi_0 + motion.mean.yaw(), node)
                                       .x.yaw();
  const CalibratedMotion g =
      calibrated_step(belief.parameters, motion.mean, psi_0, psi_guess, node);
  belief.append_calibrated(node, previous, motion, g, odometry_k_at(), odometry_ab_at());
}

bool PoseGraphCalibration::calibrates_odometry() const {
  return estimates_dvl_scale() || config_.compass_deviation;
}

Eigen::Index PoseGraphCalibration::odometry_k_at() const {
  return estimates_dvl_scale() ? constant_at(GraphConstant::kDvlScale) : -1;
}

Eigen::Index PoseGraphCalibration::odometry_ab_at() const {
  return config_.compass_deviation ? constant_at(GraphConstant::kDeviationCos) : -1;
}

CalibratedMotion PoseGraphCalibration::calibrated_step(const Eigen::VectorXd& parameters,
                                                       const Pose2& motion, double psi_from_rad,
                                                       double psi_to_rad,
                                                       std::size_t node_to) const {
  const Eigen::Index k_at = odometry_k_at(), ab_at = odometry_ab_at();
  std::optional<double> k;
  if (k_at >= 0) k = parameters(k_at);
  std::optional<Eigen::Vector2d> ab;
  Eigen::Vector2d change = Eigen::Vector2d::Zero();
  if (ab_at >= 0) {
    // The deviation's change over the motion at its two headings (the filters' model).
    ab = parameters.segment<2>(ab_at);
    change = Eigen::Vector2d(std::cos(psi_to_rad), std::sin(psi_to_rad));
    if (start_deviated(node_to)) {
      change -= Eigen::Vector2d(std::cos(psi_from_rad), std::sin(psi_from_rad));
    }
  }
  return calibrated_motion(motion, k, ab, change);
}

bool PoseGraphCalibration::start_deviated(std::size_t node) const {
  // The first motion starts from node 0, whose heading carries its reading's deviation when it
  // was taken from the compass (a start yaw with a variance), none when it is exact (the
  // filters' rule, slam/trajectory_calibration.cpp).
  return node != 1 || start_cov_(2, 2) > 1e-6;
}

std::size_t PoseGraphCalibration::bias_node(std::size_t node) const {
  // A bias that does not walk is one constant: the first scan's block.
  return config_.heading_bias_walk_deg_per_sqrt_s > 0.0 ? node : 1;
}

GaussianPose2 PoseGraphSlam::predict_match(const PoseGraphBelief& belief, Eigen::Index c,
                                           Eigen::MatrixXd* H) const {
  GaussianPose2 h = belief.predict(c, H);
  const bool clock = calibration_.config().clock_offset;
  if (!calibration_.estimates_range_scale() && !clock) return h;
  if (clock) {
    // The scans show the frames at t + tau (the filters' model, slam/calibration_model.hpp):
    // h_tau = (-)(tau u_a) (+) h (+) (tau u_b).
    const Eigen::Index t = calibration_.constant_at(GraphConstant::kClockOffset);
    const ClockShifted shifted =
        clock_shifted(h.mean, belief.parameters(t),
                      velocities_.at(belief.nodes.at(static_cast<std::size_t>(c)) - 1),
                      velocities_.at(belief.nodes.at(static_cast<std::size_t>(belief.newest)) - 1));
    h.mean = shifted.h;
    *H = shifted.d_h * *H;
    H->col(t) = shifted.d_tau;
  }
  if (calibration_.estimates_range_scale()) {
    // A match sees the scans' geometry s times the true one (the filters' model): h_s = (s t,
    // yaw), dh_s/ds = (t, 0), dh_s/d(the rest) = diag(s, s, 1) dh/d(the rest).
    const Eigen::Index r = calibration_.constant_at(GraphConstant::kRangeScale);
    const double s = belief.parameters(r);
    H->topRows<2>() *= s;
    H->block<2, 1>(0, r) = h.mean.translation();
    h.mean = Pose2(s * h.mean.x(), s * h.mean.y(), h.mean.yaw());
  }
  const Eigen::MatrixXd P = *H * belief.cov * H->transpose();
  h.cov = 0.5 * (P + P.transpose());
  return h;
}

void PoseGraphSlam::add_bias_block(std::size_t node, double t_s, PoseGraphBelief& belief) {
  const CalibrationStatesConfig& c = calibration_.config();
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
  // The filters' order (TrajectorySlam::calibration): the range scale, the DVL scale, the clock
  // offset, the bias, the deviation's a and b (deg). A constant after the smoothing solve
  // (finish): the smoothed graph's; before, online.
  const auto constant = [&](GraphConstant which, const char* name, double unit) {
    const std::size_t i = static_cast<std::size_t>(which);
    const auto& [value, sd] = smoothed_.empty() ? constant_estimates_[i] : smoothed_constants_[i];
    out.push_back({name, value * unit, sd * unit});
  };
  const std::vector<GraphConstant> constants = calibration_.estimated_constants();
  const auto has = [&](GraphConstant which) {
    return std::find(constants.begin(), constants.end(), which) != constants.end();
  };
  if (has(GraphConstant::kRangeScale)) constant(GraphConstant::kRangeScale, "range_scale", 1.0);
  if (has(GraphConstant::kDvlScale)) constant(GraphConstant::kDvlScale, "dvl_scale", 1.0);
  if (has(GraphConstant::kClockOffset)) {
    constant(GraphConstant::kClockOffset, "clock_offset_s", 1.0);
  }
  if (calibration_.estimates_heading_bias()) {
    out.push_back({"heading_bias_deg", bias_.first * kRadToDeg, bias_.second * kRadToDeg});
  }
  if (has(GraphConstant::kDeviationCos)) {
    constant(GraphConstant::kDeviationCos, "compass_deviation_cos_deg", kRadToDeg);
    constant(GraphConstant::kDeviationSin, "compass_deviation_sin_deg", kRadToDeg);
  }
  return out;
}

}  // namespace msislab
