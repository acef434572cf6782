#include "slam/line_normals.hpp"

#include <Eigen/Eigenvalues>

namespace msislab {

std::vector<Eigen::Vector2d> line_normals(const std::vector<ScanPoint>& points,
                                          const LineNormalConfig& config) {
  std::vector<Eigen::Vector2d> normals(points.size(), Eigen::Vector2d::Zero());
  const double radius2 = config.radius_m * config.radius_m;
  std::vector<Eigen::Vector2d> near;
  for (std::size_t i = 0; i < points.size(); ++i) {
    near.clear();
    for (const ScanPoint& p : points) {
      if ((p.p_m - points[i].p_m).squaredNorm() < radius2) near.push_back(p.p_m);
    }
    if (static_cast<int>(near.size()) < config.min_points) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : near) mean += p;
    mean /= static_cast<double>(near.size());
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& p : near) scatter += (p - mean) * (p - mean).transpose();
    // Eigenvalues in increasing order: the normal is the direction of least spread.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> pca(scatter);
    const Eigen::Vector2d lambda = pca.eigenvalues();
    if (lambda(1) > 0.0 && lambda(0) < config.max_eigen_ratio * lambda(1)) {
      normals[i] = pca.eigenvectors().col(0);
    }
  }
  return normals;
}

}  // namespace msislab
