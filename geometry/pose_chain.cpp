#include "geometry/pose_chain.hpp"

namespace msislab {

Pose2 compose_chain(const std::vector<Pose2>& motions, std::vector<Eigen::Matrix3d>* J_out) {
  const std::size_t n = motions.size();
  // prefix[j] = x_0 (+) ... (+) x_{j-1}; suffix[j] = x_j (+) ... (+) x_{n-1}.
  std::vector<Pose2> prefix(n + 1), suffix(n + 1);
  for (std::size_t j = 0; j < n; ++j) prefix[j + 1] = prefix[j].compose(motions[j]);
  if (!J_out) return prefix[n];
  for (std::size_t j = n; j-- > 0;) suffix[j] = motions[j].compose(suffix[j + 1]);
  J_out->resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    Eigen::Matrix3d J2;  // d(P_{j-1} (+) x_j) / d x_j
    Eigen::Matrix3d J1;  // d(A_j (+) S_{j+1}) / d A_j
    const Pose2 a = prefix[j].compose(motions[j], nullptr, &J2);
    a.compose(suffix[j + 1], &J1, nullptr);
    (*J_out)[j] = J1 * J2;
  }
  return prefix[n];
}

}  // namespace msislab
