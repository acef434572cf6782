// The runs of `msislab montecarlo`: what the workers share, the runs still to do, the scenario
// traced once, the worker processes started (one per run, app/montecarlo_worker) and the clean-up
// of what a killed worker left.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/method_catalogue.hpp"
#include "app/progress.hpp"
#include "results/montecarlo_files.hpp"
#include "sim/mesh.hpp"
#include "sim/scenario.hpp"
#include "sim/simulator.hpp"
#include "slam/slam_config.hpp"

namespace msislab::app {

/// What the workers share: the directory's settings and the inputs read once by the caller.
struct RunContext {
  results::MonteCarloManifest manifest;
  std::string dir;
  sim::Scenario scenario;
  std::string scenario_text;
  sim::TriangleMesh mesh;
  SlamConfig config;
  MethodCatalogue methods;  ///< the built-in ones and the methods file's
  int simulation_threads = 1;
  bool keep_datasets = false;
  /// The scenario's rays, traced once for every run (null: each run traces its own).
  std::shared_ptr<const sim::ScenarioTrace> trace;
};

/// A run with the methods it still lacks.
struct PendingRun {
  int run = 0;
  std::vector<std::string> methods;
};

/// The runs of `runs` with a method that has not finished (no metrics.json), in order.
std::vector<PendingRun> pending_runs(const RunContext& ctx, const std::vector<int>& runs);

/// The scenario's rays (the sonar's echoes, the DVL's altitudes), traced once on `threads` threads
/// before the workers fork (they do not depend on the seed; the workers share them copy-on-write
/// and build no scene). Ends the thread pool it used. Null when tracing fails: each run then
/// simulates whole and records its own failure.
std::shared_ptr<const sim::ScenarioTrace> trace_once(const RunContext& ctx, int threads);

/// The shared parent folders (scratch/, runs/<method>/, datasets/), made by the caller, not by the
/// workers at the same time.
void make_run_folders(const RunContext& ctx);

/// Runs `todo` in up to `jobs` worker processes (closing the directory lock's descriptor
/// `lock_fd` in each), records the methods a worker did not finish, counts finished runs in
/// `executed`; 0, or the signal that stopped the command.
int execute_runs(const RunContext& ctx, const std::vector<PendingRun>& todo, int jobs, int lock_fd,
                 Progress& progress, std::size_t& executed);

/// Removes what workers left half-written: partial run directories and datasets, scratch files
/// (of one run, or of every run).
void remove_leftovers(const std::string& dir, const std::vector<std::string>& methods,
                      std::optional<int> run = std::nullopt);

}  // namespace msislab::app
