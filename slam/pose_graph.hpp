// A pose graph over planar poses in the world frame, solved by Ceres: the back end of
// the pose-graph SLAM, beside the paper's filters. Nodes are poses [x, y, yaw]; every edge is a
// whitened residual on the project's SE(2) type with analytic Jacobians (J1+, J2+, J- of
// geometry/se2, docs/pose_algebra.md):
//   relative:  r = W A (z (-) h),  h = (-)x_i (+) x_j  (the pose of j seen from i), W A R A^T W^T =
//   I
//              (A: the observed directions as orthonormal rows, as in trajectory SLAM's matches),
//              or through a scale block s (the sonar's range scale on matches, the DVL's on
//              odometry): h_s = (s t_h, yaw_h) in place of h, with the prior r = (s - s_0) / sigma;
//   prior:     r = W (z (-) x_i);
//   heading:   r = (yaw_z - yaw_i) / sigma   (the compass), or (yaw_z - yaw_i - b_i) / sigma
//              through node i's heading bias b_i (a scalar block; the compass's walking bias,
//              docs/pose_graph.md), whose walk is r = (b_j - b_i) / (q sqrt(dt)) and prior
//              r = (b_i - b_0) / sigma.
// Analytic rather than automatic Jacobians: the pose algebra already has them, checked against
// central differences in tests, and the residuals stay written in the same SE(2) type every filter
// uses (Ceres' Jets would need a templated copy of it).
// Match edges may carry a robust loss (dynamic covariance scaling by default, or Cauchy, on the
// squared whitened norm): a wrong match that slipped past the validation costs little, and the
// edges it down-weights are counted.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "geometry/se2.hpp"

namespace ceres {
class Problem;
class LossFunction;
}  // namespace ceres

namespace msislab {

/// The robust loss on match edges, on the squared whitened norm s with scale c^2:
/// - dynamic covariance scaling (Agarwal et al., ICRA 2013), as the kernel it amounts to: the
///   edge's information scaled by min(1, 2 c^2 / (c^2 + s))^2, i.e. rho(s) = s inside the gate
///   (s <= c^2: a consistent match counts in full, so the covariances stay those of a Gaussian
///   graph) and rho(s) = 3 c^2 - 4 c^4 / (c^2 + s) beyond it: bounded, an edge far beyond the
///   gate pulls with a force that vanishes like 1 / s^2;
/// - Cauchy: rho(s) = c^2 log(1 + s / c^2): unbounded, so a soft graph still gives way to a far
///   outlier in proportion to the log of the residual it removes, and it discounts consistent
///   matches too (tests/slam/pose_graph_test.cpp measures both).
enum class RobustLoss { kDynamicCovarianceScaling, kCauchy };

/// The graph's constants (one scalar block each): the sonar's range scale, the DVL's scale factor,
/// the sonar clock's offset (s), the compass's one-cycle deviation d(psi) = a cos(psi) + b sin(psi)
/// (a and b, rad).
enum class GraphConstant {
  kRangeScale = 0,
  kDvlScale = 1,
  kClockOffset = 2,
  kDeviationCos = 3,
  kDeviationSin = 4
};

struct PoseGraphConfig {
  RobustLoss robust_loss = RobustLoss::kDynamicCovarianceScaling;
  /// c^2, as a squared whitened norm: the chi-square 99 % gate of 3 DOF (11.34). 0: no robust
  /// loss.
  double robust_scale_chi2 = 11.34;
  /// Graduated start: each solve first runs with c^2 times this, then at c^2, so that a loop
  /// closure found after a long drift (its edge far beyond the gate at the drifted estimate) pulls
  /// the graph before the kernel judges it. 1: one solve at c^2.
  double robust_start_factor = 100.0;
  int max_iterations = 100;
};

/// What a solve did.
struct PoseGraphSolve {
  bool converged = false;   ///< Ceres reported convergence (not an iteration or time limit)
  double final_cost = 0.0;  ///< Ceres' cost: half the sum of the (robustified) squared residuals
  /// Robust edges beyond the gate at the solution (squared whitened norm above
  /// robust_scale_chi2): the matches the loss set aside.
  int edges_downweighted = 0;
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphConfig& config = {});
  ~PoseGraph();
  PoseGraph(const PoseGraph&) = delete;
  PoseGraph& operator=(const PoseGraph&) = delete;

  /// Adds a node at its initial (world) pose; returns its index.
  std::size_t add_node(const Pose2& initial_world);
  std::size_t nodes() const { return poses_.size(); }
  /// Holds a node where it is (the gauge; a prior with a singular covariance).
  void fix_node(std::size_t i);
  /// Holds the nodes before `first_free` where they are in the following solves (a windowed
  /// online solve); 0 frees them all again. Fixed nodes stay fixed.
  void hold_before(std::size_t first_free);
  /// Holds the constants where they are in the following solves (held: a windowed online solve,
  /// whose held nodes would inform them as if exact), or frees them again. covariances() and
  /// joint_covariance() free them, as they free the held nodes.
  void hold_constants(bool held);
  /// The add_* below throw std::out_of_range for a node that does not exist and
  /// std::invalid_argument for a covariance that is not positive definite, before anything is
  /// allocated or added (a refused input leaks nothing).
  /// z ~ x_i with covariance cov (positive definite).
  void add_prior(std::size_t i, const GaussianPose2& z_world);
  /// z ~ A ((-)x_i (+) x_j): the pose of node j seen from node i, in the directions whose
  /// orthonormal rows A holds (3 x 3 identity: all), z's covariance cov (3 x 3). robust: under
  /// the robust loss of the config (the matches; odometry is not).
  void add_relative(std::size_t i, std::size_t j, const GaussianPose2& z,
                    const Eigen::MatrixXd& observed, bool robust);
  /// The compass: yaw_world_rad ~ yaw_i with standard deviation sigma_rad; through the deviation,
  /// yaw_i + a cos(yaw_i) + b sin(yaw_i), where the graph has its two constants.
  void add_heading(std::size_t i, double yaw_world_rad, double sigma_rad);
  /// The dead-reckoning motion z from node i to node j (not robust): as add_relative, through the
  /// DVL's scale and the compass's deviation where the graph has them (its heading change carries
  /// d(yaw_j) - d(yaw_i), or d(yaw_j) alone when start_deviated is false: node i's heading was not
  /// read from the compass, an exact start; slam/pose_graph_edges.hpp, OdometryCost).
  void add_odometry(std::size_t i, std::size_t j, const GaussianPose2& z, bool start_deviated);

  /// Gives node i a heading-bias block at initial_rad (held there when fixed: known). Throws
  /// std::invalid_argument when it has one already.
  void add_heading_bias(std::size_t i, double initial_rad, bool fixed);
  /// b_i ~ N(mean_rad, sigma_rad^2). The bias add_* throw std::out_of_range for a node without a
  /// bias block.
  void add_heading_bias_prior(std::size_t i, double mean_rad, double sigma_rad);
  /// b_j - b_i ~ N(0, sigma_rad^2): the bias's walk from node i to node j.
  void add_heading_bias_walk(std::size_t i, std::size_t j, double sigma_rad);
  /// The compass through a bias: yaw_world_rad ~ yaw_i + b_k (k = bias_node: node i's own, or
  /// the one a constant bias lives in), standard deviation sigma_rad; through the deviation too
  /// where the graph has it, as add_heading.
  void add_biased_heading(std::size_t i, std::size_t bias_node, double yaw_world_rad,
                          double sigma_rad);
  /// A constant, one block for the whole graph, at `initial`, with the prior
  /// c ~ N(prior_mean, prior_sigma^2): the sonar's range scale (the scans' geometry is s times
  /// the true one, so a match sees it), the DVL's (its velocities are k times the true ones, so
  /// an odometry edge sees it), the sonar clock's offset tau (a match sees scans moved by tau times
  /// their velocities), the compass deviation's a and b (the compass and odometry edges added
  /// after both see them). Throws std::invalid_argument when it exists already.
  void add_constant(GraphConstant which, double initial, double prior_mean, double prior_sigma);
  bool has_constant(GraphConstant which) const { return has_constant_[index(which)]; }
  double constant(GraphConstant which) const { return constants_[index(which)]; }
  /// Moves a constant (a warm start for the next solve).
  void set_constant(GraphConstant which, double c) { constants_[index(which)] = c; }
  /// A match: as add_relative, through the graph's clock offset tau and range scale s where it has
  /// them: h_tau = (-)(tau u_i) (+) h (+) (tau u_j), u_i and u_j the two scans' velocities
  /// (Scan::velocity_vehicle), then (s t, yaw) of that.
  void add_match(std::size_t i, std::size_t j, const GaussianPose2& z,
                 const Eigen::MatrixXd& observed, const Eigen::Vector3d& u_i,
                 const Eigen::Vector3d& u_j);
  double heading_bias(std::size_t i) const;
  /// Moves a bias (a warm start for the next solve).
  void set_heading_bias(std::size_t i, double bias_rad);

  /// Solves from the current poses (warm start: each solve starts where the last ended).
  /// count_downweighted: evaluate every robust edge afterwards for edges_downweighted (else 0).
  PoseGraphSolve solve(bool count_downweighted = true);

  Pose2 pose(std::size_t i) const;
  /// The marginal covariances of the given nodes at the current poses (the whole graph's
  /// information J^T J, robust edges at their weight there, factored by sparse Cholesky; held
  /// nodes are freed first, and stay free, fixed ones have zero covariance). Throws
  /// std::runtime_error when the graph's information is singular (a node without a path to a
  /// prior or fixed node).
  std::vector<Eigen::Matrix3d> covariances(const std::vector<std::size_t>& nodes);
  /// The joint marginal covariance of the given (distinct) nodes, 3n x 3n in their order (one
  /// factorisation, as covariances()). With between() of geometry/gaussian_pose, what the graph
  /// knows of the pose of one node seen from another, which the odometry chain alone overstates
  /// once loops close. Throws as covariances() does.
  /// bias_nodes: first, the heading biases of these nodes, then the given scales (each must
  /// exist) ((b + s + 3n) square, the parameters leading).
  Eigen::MatrixXd joint_covariance(const std::vector<std::size_t>& nodes,
                                   const std::vector<std::size_t>& bias_nodes = {},
                                   const std::vector<GraphConstant>& scales = {});
  /// Moves a node (a warm start for the next solve).
  void set_pose(std::size_t i, const Pose2& world);

  /// The Ceres problem, for checks (tests compare its residuals' Jacobians with numeric ones).
  const ceres::Problem& problem_for_checks() const;

 private:
  struct Problem;
  static constexpr std::size_t kMaxNodes = std::size_t{1} << 20;  ///< 32 MB of address space
  PoseGraphConfig config_;
  /// The nodes' poses in one buffer reserved up front for kMaxNodes (address space only: its
  /// pages are touched as nodes come), so that their addresses never move (Ceres holds them) and
  /// increase with the node index: nothing the solver does then depends on the memory layout
  /// (the environment's size, the output path's length), for "same seed, same bytes".
  std::vector<Eigen::Vector3d> poses_;
  std::vector<double> biases_;    ///< per node its heading bias (a block where has_bias_), reserved
  std::vector<bool> fixed_;       ///< per node: held for good (the gauge)
  std::vector<bool> has_bias_;    ///< per node: it has a heading-bias block
  std::vector<bool> bias_fixed_;  ///< per node: that block held for good
  std::size_t held_before_ = 0;   ///< nodes before this are held for now (hold_before)
  /// Blocks where has_constant_ (the object never moves).
  std::array<double, 5> constants_{1.0, 1.0, 0.0, 0.0, 0.0};
  std::array<bool, 5> has_constant_{false, false, false, false, false};
  bool constants_held_ = false;
  static std::size_t index(GraphConstant which) { return static_cast<std::size_t>(which); }
  /// The scales' blocks that exist, in GraphConstant order, for the information's columns.
  std::vector<double*> constant_blocks();
  /// Both of the deviation's constants exist.
  bool has_deviation() const;
  /// The deviation's two blocks appended to an edge's.
  void append_deviation(std::vector<double*>& blocks);
  std::unique_ptr<Problem> problem_;

  double* bias_block(std::size_t i);  ///< node i's bias block; throws when it has none
  /// The configured robust loss for a match edge (robust), else none.
  ceres::LossFunction* robust_loss(bool robust);
};

}  // namespace msislab
