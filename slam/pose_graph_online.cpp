// The pose-graph SLAM's whole-graph online belief (WholeGraphOnline,
// PoseGraphSlamConfig::online_window_scans = 0; slam/pose_graph_online.hpp): each scan's node
// composed onto the previous one, the candidates' joint with it from the whole graph's
// information.
#include "slam/pose_graph_online.hpp"

#include <optional>
#include <utility>

namespace msislab {

WholeGraphOnline::WholeGraphOnline(PoseGraph& graph, const PoseGraphCalibration& calibration,
                                   const Eigen::MatrixXd& start_joint)
    : graph_(graph), calibration_(calibration), newest_joint_(start_joint) {}

PoseGraphBelief WholeGraphOnline::odometry_belief(std::size_t node, const GaussianPose2& motion) {
  // The odometry edge (Eq. 2): the newest node's belief is the previous one's composed with the
  // motion, exact for its marginal since nothing else touches it yet.
  const Eigen::VectorXd parameters =
      calibration_.graph_parameters(node == 1 ? std::nullopt : std::optional(node - 1));
  if (parameters.size() > 0) {
    // The calibration's joint with the newest node, carried from scan to scan; the previous node
    // marginalised once the new one is composed onto it.
    PoseGraphBelief chain{{node - 1}, {graph_.pose(node - 1)}, newest_joint_, 0, parameters};
    calibration_.append_odometry(chain, node, 0, motion);
    return {{node}, {chain.means[1]}, chain.marginal({1}), 0, chain.parameters};
  }
  const GaussianPose2 previous{graph_.pose(node - 1), newest_joint_};
  const GaussianPose2 newest = compose(previous, motion);
  return {{node}, {newest.mean}, newest.cov, 0, {}};
}

std::vector<Eigen::Index> WholeGraphOnline::join_candidates(std::size_t k,
                                                            const PoseGraphCandidates& candidates,
                                                            PoseGraphBelief& belief) {
  const std::size_t node = k + 1;
  PoseGraphBelief joint;
  for (const auto& candidate : candidates) {
    joint.nodes.push_back(candidate.second + 1);
    joint.means.push_back(graph_.pose(candidate.second + 1));
  }
  joint.nodes.push_back(node);
  joint.means.push_back(belief.means[static_cast<std::size_t>(belief.newest)]);
  joint.newest = static_cast<Eigen::Index>(candidates.size());
  joint.parameters = calibration_.graph_parameters(node);
  std::vector<std::size_t> bias_nodes;
  if (calibration_.estimates_heading_bias()) bias_nodes.push_back(calibration_.bias_node(node));
  joint.cov = graph_.joint_covariance(joint.nodes, bias_nodes, calibration_.estimated_constants());
  belief = std::move(joint);
  std::vector<Eigen::Index> in_belief;
  for (Eigen::Index c = 0; c < belief.newest; ++c) in_belief.push_back(c);
  return in_belief;
}

void WholeGraphOnline::keep(const PoseGraphBelief& belief, std::size_t /*k*/) {
  if (belief.parameters.size() > 0) {
    newest_joint_ = belief.marginal({belief.newest});
  } else {
    newest_joint_ = belief.node_cov(belief.newest);
  }
}

}  // namespace msislab
