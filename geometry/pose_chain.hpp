// Compositions of chains of relative motions, the observation function of trajectory SLAM
// (paper Eq. 5-8): the pose of scan b in the frame of scan a is x_{a+1} (+) ... (+) x_b.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/se2.hpp"

namespace msislab {

/// T = x_0 (+) x_1 (+) ... (+) x_{n-1} (identity for an empty chain). With J_out, also the
/// Jacobian of T with respect to every x_j: J_j = J1+(A_j, S_{j+1}) J2+(P_{j-1}, x_j), where
/// P_{j-1} is the prefix before x_j, A_j = P_{j-1} (+) x_j and S_{j+1} the suffix after it.
Pose2 compose_chain(const std::vector<Pose2>& motions,
                    std::vector<Eigen::Matrix3d>* J_out = nullptr);

}  // namespace msislab
