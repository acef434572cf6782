// `msislab montecarlo SCENARIO.yaml --runs N --out DIR [--methods a,b] [--jobs J]
// [--config SLAM.yaml] [--shard i/N] [--keep-datasets]` and `msislab montecarlo merge OUT_DIR
// SHARD_DIR...`: N seeded repetitions of simulate + every method, each run in a forked worker
// process that simulates into memory and hands the dataset straight to the methods; resumable,
// shardable, one writer per directory, summarised into consistency statistics (docs/cli.md,
// docs/formats.md).
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "eval/monte_carlo.hpp"

namespace msislab::app {

struct MonteCarloOptions {
  std::string scenario_path;
  int runs = 0;
  std::string out_dir;
  std::vector<std::string> methods = {"robocentric", "worldcentric"};
  int jobs = 0;                ///< concurrent runs; 0: one per hardware thread
  std::string config_path;     ///< SLAM config for every run; empty: the defaults
  std::string shard;           ///< "i/N": only the runs r with r % N == i; empty: every run
  bool keep_datasets = false;  ///< also write each run's dataset to DIR/datasets/run_<rrrr>
  std::string methods_file{};  ///< external methods (docs/formats.md); empty: none
};

/// Where the messages go: progress on `log` (a bar redrawn in place when `terminal`).
struct MonteCarloLog {
  std::ostream& log;
  bool terminal = false;
};

struct MonteCarloOutcome {
  std::size_t runs = 0;      ///< runs in this directory (its shard)
  std::size_t executed = 0;  ///< runs (re)done by this call; the others were finished already
  std::size_t failed = 0;    ///< runs with at least one failed method
  /// The stop request (SIGINT, SIGTERM, SIGHUP) that ended the runs early, else 0. Then the
  /// finished runs are kept, no summary is written, and the same command resumes.
  int interrupted = 0;
  std::vector<MethodSummary> summary;
};

/// InputError unless shard is empty or "i/N" (0 <= i < N; parsed into index and count, else
/// 0 and 1) and jobs >= 0.
void check_shard_and_jobs(const std::string& shard, int jobs, int& shard_index, int& shard_count);

/// Checks every input (methods, shard, scenario, its mesh, config, an existing DIR made from the
/// same scenario and config by this build), locks DIR (InputError naming the holder when another
/// command has it), then runs what is not finished yet and writes DIR/summary.json, DIR/nees.csv
/// and DIR/seeds.csv. A run that fails or crashes is recorded (failed.json), not thrown; a stop
/// request ends the workers and returns with `interrupted` set. Throws io::InputError.
MonteCarloOutcome montecarlo(const MonteCarloOptions& options, const MonteCarloLog& log);

struct MergeOptions {
  std::string out_dir;
  std::vector<std::string> shard_dirs;
};

/// Draws the figures of a finished Monte Carlo (or sweep) directory into DIR/figures by running
/// `msislab plot DIR` as a child process of `executable` (empty: this process's), which finds or
/// starts an X display itself. Returns an empty string, or why no figure was drawn (the last line
/// the plot command wrote to stderr). A missing figure does not undo the statistics.
std::string draw_montecarlo_figures(const std::string& dir, const std::string& executable = "");

/// Copies the finished and failed runs of the shard directories (made by montecarlo with the same
/// scenario, config, runs and methods) into out_dir and writes its summary over every run.
MonteCarloOutcome merge_montecarlo(const MergeOptions& options);

}  // namespace msislab::app
