// sim/marina_trace on a synthetic basin with an opening, a moored box and one stray echo: the
// opening stays open (water beyond, no wall), the walls are traced where they are, the box becomes
// one clutter object and the echo seen once is rejected.
#include "sim/marina_trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "sim/polygon_triangulation.hpp"

namespace msislab::sim {
namespace {

using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

/// A 40 x 20 m basin whose east wall has an 8 m opening (y 6..14), and a 2 x 2 m box.
std::vector<Segment> scene() {
  std::vector<Segment> s = {{{0, 0}, {40, 0}},    {{40, 0}, {40, 6}},   {{40, 14}, {40, 20}},
                            {{40, 20}, {0, 20}},  {{0, 20}, {0, 0}},    {{18, 13}, {20, 13}},
                            {{20, 13}, {20, 15}}, {{20, 15}, {18, 15}}, {{18, 15}, {18, 13}}};
  return s;
}

std::optional<double> first_hit_m(const Eigen::Vector2d& p, const Eigen::Vector2d& d) {
  std::optional<double> nearest;
  for (const auto& [a, b] : scene()) {
    const Eigen::Vector2d e = b - a, w = a - p;
    const double det = d.x() * -e.y() + e.x() * d.y();
    if (std::abs(det) < 1e-12) continue;
    const double t = (w.x() * -e.y() + e.x() * w.y()) / det;
    const double u = (d.x() * w.y() - d.y() * w.x()) / det;
    if (t > 0.0 && t <= 50.0 && u >= 0.0 && u <= 1.0 && (!nearest || t < *nearest)) nearest = t;
  }
  return nearest;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const double u = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (a + u * (b - a) - p).norm();
}

struct SyntheticRun {
  std::vector<TraceBeam> beams;
  std::vector<Eigen::Vector2d> track_m;
};

/// A loop around the box at 0.25 m/s, 200 beams per 13.8 s revolution, ranges jittered +-0.2 m.
SyntheticRun simulate_run() {
  const std::vector<Eigen::Vector2d> corners = {{5, 5}, {35, 5}, {35, 17.5}, {5, 17.5}, {5, 5}};
  SyntheticRun run;
  const double dt_s = 13.8 / 200.0, speed_mps = 0.25;
  std::size_t leg = 0;
  Eigen::Vector2d p = corners[0];
  for (int k = 0; leg + 1 < corners.size(); ++k) {
    const Eigen::Vector2d to_next = corners[leg + 1] - p;
    if (to_next.norm() < speed_mps * dt_s) {
      p = corners[++leg];
      continue;
    }
    p += to_next.normalized() * speed_mps * dt_s;
    TraceBeam beam;
    beam.t_s = k * dt_s;
    beam.revolution = k / 200;
    beam.head_world_m = p;
    beam.bearing_world_rad = -2.0 * M_PI * (k % 200) / 200.0;
    const Eigen::Vector2d d(std::cos(beam.bearing_world_rad), std::sin(beam.bearing_world_rad));
    if (const auto range_m = first_hit_m(p, d)) {
      beam.first_range_m = *range_m + 0.2 * std::sin(12.9898 * k);
    }
    if (k == 1500) {  // one stray echo in open water, seen once
      beam.first_range_m = 0.0;
      const Eigen::Vector2d stray(28.0, 11.0);
      beam.bearing_world_rad = std::atan2(stray.y() - p.y(), stray.x() - p.x());
      beam.first_range_m = (stray - p).norm();
    }
    run.beams.push_back(beam);
    if (k % 15 == 0) run.track_m.push_back(p);
  }
  return run;
}

bool inside(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

class MarinaTraceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const SyntheticRun run = simulate_run();
    trace_ = new MarinaTrace(trace_marina(run.beams, run.track_m, MarinaTraceConfig{}));
  }
  static void TearDownTestSuite() { delete trace_; }
  static MarinaTrace* trace_;
};
MarinaTrace* MarinaTraceTest::trace_ = nullptr;

TEST_F(MarinaTraceTest, OpeningStaysOpenWithWaterBeyond) {
  const BasinOutline& outline = trace_->outline;
  ASSERT_EQ(outline.ccw_polygon_m.size(), outline.wall_edge.size());
  EXPECT_GT(signed_double_area(outline.ccw_polygon_m), 0.0);
  EXPECT_FALSE(find_crossing_edges(outline.ccw_polygon_m));
  EXPECT_TRUE(inside(outline.ccw_polygon_m, {45.0, 10.0})) << "water beyond the opening";
  EXPECT_TRUE(inside(outline.ccw_polygon_m, {20.0, 10.0}));
}

// Tolerances: the outline lies wall_offset_m (1 m) into the band of echo cells, which here is
// about 0.5 m thick (0.25 m cells, ranges jittered +-0.2 m), so it ends up to 0.75 m beyond the
// true wall; at the end of a wall (the opening) it wraps around the band's end, up to 1.1 m off.
TEST_F(MarinaTraceTest, WallEdgesLieOnTheWallsAndEveryWallIsTraced) {
  const BasinOutline& outline = trace_->outline;
  const auto& p = outline.ccw_polygon_m;
  const std::vector<Segment> all = scene();
  const std::vector<Segment> walls(all.begin(), all.begin() + 5);
  const auto distance_to_walls = [&](const Eigen::Vector2d& q) {
    double d = 1e9;
    for (const auto& [a, b] : walls) d = std::min(d, distance_to_segment(q, a, b));
    return d;
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!outline.wall_edge[i]) continue;
    const Eigen::Vector2d middle = 0.5 * (p[i] + p[(i + 1) % p.size()]);
    EXPECT_LT(distance_to_walls(middle), 1.1) << "wall edge " << i << " off every wall";
  }
  for (const auto& [a, b] : walls) {
    const double length_m = (b - a).norm();
    for (double s_m = 1.0; s_m < length_m - 1.0; s_m += 1.0) {
      const Eigen::Vector2d q = a + (b - a) * s_m / length_m;
      double nearest_m = 1e9;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (outline.wall_edge[i]) {
          nearest_m = std::min(nearest_m, distance_to_segment(q, p[i], p[(i + 1) % p.size()]));
        }
      }
      EXPECT_LT(nearest_m, 0.75) << "wall point (" << q.x() << ", " << q.y() << ")";
    }
  }
}

TEST_F(MarinaTraceTest, BoxBecomesOneClutterObjectAndTheStrayEchoIsRejected) {
  ASSERT_EQ(trace_->clutter.size(), 1u);
  const ClutterObject& box = trace_->clutter.front();
  EXPECT_LT((box.centre_m - Eigen::Vector2d(19.0, 14.0)).norm(), 0.5);
  EXPECT_NEAR(box.length_m * box.width_m, 4.0, 2.5);
  EXPECT_GE(box.revolutions, 3);
  EXPECT_GE(trace_->rejected_clusters, 1);
}

}  // namespace
}  // namespace msislab::sim
