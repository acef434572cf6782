#include "sim/polygon_triangulation.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace msislab::sim {
namespace {

/// Twice the signed area of the triangle (a, b, c): > 0 when counter-clockwise.
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a;
  const Eigen::Vector2d ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

bool inside_or_on(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                  const Eigen::Vector2d& c) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

/// Whether segments ab and cd cross or touch (Cormen et al., section 33.1).
bool segments_intersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const auto side = [](double z) { return (z > 0.0) - (z < 0.0); };
  const int o1 = side(cross(a, b, c)), o2 = side(cross(a, b, d));
  const int o3 = side(cross(c, d, a)), o4 = side(cross(c, d, b));
  if (o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0) {  // collinear: do the extents overlap?
    return (a.cwiseMin(b).array() <= c.cwiseMax(d).array()).all() &&
           (c.cwiseMin(d).array() <= a.cwiseMax(b).array()).all();
  }
  return o1 * o2 <= 0 && o3 * o4 <= 0;
}

/// The polygon still to be clipped: indices into the input, in counter-clockwise order.
class Ring {
 public:
  explicit Ring(const std::vector<Eigen::Vector2d>& polygon) : polygon_(polygon) {
    for (int i = 0; i < static_cast<int>(polygon.size()); ++i) indices_.push_back(i);
  }
  std::size_t size() const { return indices_.size(); }
  int prev(std::size_t k) const { return indices_[(k + size() - 1) % size()]; }
  int at(std::size_t k) const { return indices_[k]; }
  int next(std::size_t k) const { return indices_[(k + 1) % size()]; }
  const Eigen::Vector2d& point(int index) const { return polygon_[index]; }
  void erase(std::size_t k) { indices_.erase(indices_.begin() + static_cast<std::ptrdiff_t>(k)); }

  /// The first vertex from `start` on (wrapping around) that satisfies `test`.
  std::optional<std::size_t> find(std::size_t start, bool (Ring::*test)(std::size_t) const) const {
    for (std::size_t i = 0; i < size(); ++i) {
      const std::size_t k = (start + i) % size();
      if ((this->*test)(k)) return k;
    }
    return std::nullopt;
  }

  /// A vertex on the line through its neighbours (or repeating one): removable without a triangle.
  bool degenerate(std::size_t k) const {
    const Eigen::Vector2d& a = point(prev(k));
    const Eigen::Vector2d& b = point(at(k));
    const Eigen::Vector2d& c = point(next(k));
    return std::abs(cross(a, b, c)) <= 1e-12 * (b - a).norm() * (c - b).norm();
  }

  /// Convex corner whose triangle holds no other remaining vertex.
  bool ear(std::size_t k) const {
    const Eigen::Vector2d& a = point(prev(k));
    const Eigen::Vector2d& b = point(at(k));
    const Eigen::Vector2d& c = point(next(k));
    if (cross(a, b, c) <= 0.0) return false;
    for (const int index : indices_) {
      const Eigen::Vector2d& p = point(index);
      if (p == a || p == b || p == c) continue;
      if (inside_or_on(p, a, b, c)) return false;
    }
    return true;
  }

 private:
  const std::vector<Eigen::Vector2d>& polygon_;
  std::vector<int> indices_;
};

}  // namespace

double signed_double_area(const std::vector<Eigen::Vector2d>& polygon) {
  double area2 = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
  }
  return area2;
}

std::optional<std::pair<int, int>> find_crossing_edges(
    const std::vector<Eigen::Vector2d>& polygon) {
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_intersect(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n])) {
        return std::make_pair(i, j);
      }
    }
  }
  return std::nullopt;
}

std::vector<Eigen::Vector3i> triangulate_polygon(const std::vector<Eigen::Vector2d>& ccw_polygon) {
  if (ccw_polygon.size() < 3) {
    throw std::invalid_argument("triangulate_polygon: " + std::to_string(ccw_polygon.size()) +
                                " vertices, need at least 3");
  }
  if (signed_double_area(ccw_polygon) <= 0.0) {
    throw std::invalid_argument("triangulate_polygon: polygon is clockwise or has zero area");
  }
  Ring ring(ccw_polygon);
  std::vector<Eigen::Vector3i> triangles;
  std::size_t k = 0;
  while (ring.size() > 3) {
    if (const std::optional<std::size_t> ear = ring.find(k, &Ring::ear)) {
      k = *ear;
      triangles.emplace_back(ring.prev(k), ring.at(k), ring.next(k));
      ring.erase(k);
    } else if (const std::optional<std::size_t> flat = ring.find(0, &Ring::degenerate)) {
      ring.erase(*flat);  // only when no ear is left, so that no T-junction is made otherwise
    } else {
      throw std::invalid_argument("triangulate_polygon: no ear left (self-intersecting polygon?)");
    }
  }
  if (!ring.degenerate(1)) triangles.emplace_back(ring.at(0), ring.at(1), ring.at(2));
  return triangles;
}

}  // namespace msislab::sim
