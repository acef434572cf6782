// The Ceres problem behind a PoseGraph and the robust edges in it: internal to slam/pose_graph*.cpp
// (the graph's edges and solves in pose_graph.cpp, its information in pose_graph_information.cpp).
#pragma once

#include <ceres/ceres.h>

#include <vector>

#include "slam/pose_graph.hpp"

namespace msislab {

struct PoseGraph::Problem {
  ceres::Problem problem;
  /// The robust edges, to count the down-weighted ones after a solve.
  std::vector<ceres::ResidualBlockId> robust;
  /// c^2 of the robust losses now: the configured one, or more during a graduated start.
  double c2 = 0.0;
};

}  // namespace msislab
