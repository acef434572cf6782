// Trajectory SLAM step time against state size: a synthetic basin loop driven until the
// state holds N scans, timing the scans added after that (each matched against up to 3 earlier
// scans and updated), for both filters; with the update restricted to the loop's window (the
// default) or over the whole state, and with or without the per-scan compass update (which
// involves every element). items_per_second is scans per second at that state size. The pose
// graph's step time on the same scans, up to 2,000 scans, closes the file.
#include <benchmark/benchmark.h>

#include <random>

#include "slam/pose_graph_slam.hpp"
#include "slam/robocentric_slam.hpp"
#include "slam/worldcentric_slam.hpp"

namespace {

using namespace msislab;

std::vector<Eigen::Vector2d> basin_walls() {
  std::vector<Eigen::Vector2d> points;
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.5);
    for (int i = 0; i <= n; ++i) points.push_back(a + (b - a) * i / n);
  };
  wall({-20, -15}, {20, -15});
  wall({20, -15}, {20, 15});
  wall({20, 15}, {-20, 15});
  wall({-20, 15}, {-20, -15});
  wall({0, 15}, {0, 8});
  return points;
}

/// Scans every 4 m around a 24 x 16 m loop, repeated; about 150 points each.
std::vector<Scan> loop_scans(std::size_t count) {
  std::mt19937 rng(1);
  std::normal_distribution<double> n01(0.0, 1.0);
  const auto world = basin_walls();
  std::vector<Pose2> path;
  while (path.size() < count) {
    for (int i = 0; i < 6; ++i) path.emplace_back(-12.0 + 4 * i, -8.0, 0.0);
    for (int i = 0; i < 4; ++i) path.emplace_back(12.0, -8.0 + 4 * i, M_PI / 2);
    for (int i = 0; i < 6; ++i) path.emplace_back(12.0 - 4 * i, 8.0, M_PI);
    for (int i = 0; i < 4; ++i) path.emplace_back(-12.0, 8.0 - 4 * i, -M_PI / 2);
  }
  path.resize(count);
  std::vector<Scan> scans;
  for (std::size_t k = 0; k < count; ++k) {
    Scan scan;
    const Pose2 motion = k == 0 ? path[0] : path[k - 1].between(path[k]);
    scan.motion.mean = Pose2(motion.vector() +
                             Eigen::Vector3d(0.05 * n01(rng), 0.05 * n01(rng), 0.005 * n01(rng)));
    scan.motion.cov = Eigen::Vector3d(0.0025, 0.0025, 2.5e-5).asDiagonal();
    scan.compass_yaw_world_rad = normalize_angle(path[k].yaw() + 0.017 * n01(rng));
    scan.compass_sigma_rad = 0.017;
    for (const auto& p_world : world) {
      const Eigen::Vector2d p = path[k].inverse().transform(p_world);
      if (p.norm() > 25.0) continue;
      ScanPoint point;
      point.p_m = p + 0.05 * Eigen::Vector2d(n01(rng), n01(rng));
      point.cov = 0.0025 * Eigen::Matrix2d::Identity();
      point.cov_reading = point.cov;
      scan.points.push_back(point);
    }
    scans.push_back(scan);
  }
  return scans;
}

/// Args: state size in scans, compass updates (0/1), whole-state update (0/1).
template <class Filter>
void BM_Step(benchmark::State& state) {
  const auto state_scans = static_cast<std::size_t>(state.range(0));
  TrajectorySlamConfig config;
  config.front_end.compass_updates = state.range(1) != 0;
  config.filter.update_whole_state = state.range(2) != 0;
  const std::size_t timed = 10;
  const std::vector<Scan> scans = loop_scans(state_scans + timed);
  for (auto _ : state) {
    state.PauseTiming();
    Filter slam(config, GaussianPose2{});
    for (std::size_t k = 0; k < state_scans; ++k) slam.add_scan(scans[k]);
    state.ResumeTiming();
    for (std::size_t k = state_scans; k < scans.size(); ++k) {
      benchmark::DoNotOptimize(slam.add_scan(scans[k]));
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(timed));
  state.counters["state_dim"] = static_cast<double>(3 * state_scans);
}

void step_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"scans", "compass", "whole"});
  for (int n : {25, 50, 100, 200, 400}) {
    b->Args({n, 0, 0})->Args({n, 0, 1})->Args({n, 1, 0});
  }
  // A long mission (tools/step_time_figure.sh): the default config only, the covariance dense
  // (2,000 scans: 6,000 x 6,000, 288 MB).
  for (int n : {1000, 2000}) b->Args({n, 1, 0});
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK_TEMPLATE(BM_Step, RoboCentricSlam)->Apply(step_args);
BENCHMARK_TEMPLATE(BM_Step, WorldCentricSlam)->Apply(step_args);

/// The pose graph on the same scans: step time (match, solve, the newest scan's
/// covariance) against graph size, up to a long mission of 2,000 scans. Args: scans in the graph,
/// solve_every, online_window_scans (0: the whole graph each step).
void BM_PoseGraphStep(benchmark::State& state) {
  const auto graph_scans = static_cast<std::size_t>(state.range(0));
  PoseGraphSlamConfig config;
  config.solve_every = static_cast<int>(state.range(1));
  config.online_window_scans = static_cast<int>(state.range(2));
  const std::size_t timed = 10;
  const std::vector<Scan> scans = loop_scans(graph_scans + timed);
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraphSlam slam(ScanFrontEndConfig{}, CalibrationStatesConfig{}, config, GaussianPose2{});
    for (std::size_t k = 0; k < graph_scans; ++k) slam.add_scan(scans[k]);
    state.ResumeTiming();
    for (std::size_t k = graph_scans; k < scans.size(); ++k) {
      benchmark::DoNotOptimize(slam.add_scan(scans[k]));
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(timed));
}
void pose_graph_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"scans", "solve_every", "window"});
  // The whole graph each step: the step time grows with the graph, and the 2,000-scan row is slow
  // to set up (docs/pose_graph.md, "Long missions", has the measured times).
  for (int n : {100, 200, 500, 1000, 2000}) b->Args({n, 1, 0});
  b->Args({500, 10, 0});
  for (int n : {100, 200, 500, 1000, 2000}) b->Args({n, 1, 100});
  b->Unit(benchmark::kMillisecond)->Iterations(1);
}
BENCHMARK(BM_PoseGraphStep)->Apply(pose_graph_args);

}  // namespace
