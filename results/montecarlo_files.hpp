// The files of a Monte Carlo directory (docs/formats.md): montecarlo.json (the settings),
// seeds.csv, summary.json, nees.csv, and a run's failed.json.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "eval/monte_carlo.hpp"
#include "io/json.hpp"

namespace msislab::results {

/// montecarlo.json: how the directory was made.
struct MonteCarloManifest {
  std::string scenario_source;   ///< absolute path of the scenario that was copied to scenario.yaml
  std::uint64_t first_seed = 0;  ///< the scenario's seed: run r used first_seed + r
  int runs = 0;                  ///< N: runs 0 .. N-1
  std::vector<std::string> methods;
  bool has_config = false;        ///< config.yaml holds the SLAM config every run used
  bool has_methods_file = false;  ///< methods.yaml: a copy of the --methods-file given
  int shard_index = 0;  ///< this directory holds the runs r with r % shard_count == shard_index
  int shard_count = 1;
  /// Which msislab executable made the runs (app::executable_digest); empty in directories made
  /// before it was recorded. Runs of two builds are never mixed.
  std::string executable_digest;
};
void to_json(io::Json& json, const MonteCarloManifest& manifest);
void from_json(const io::JsonObject& json, MonteCarloManifest& manifest);
void write_manifest_json(const std::string& path, const MonteCarloManifest& manifest);
MonteCarloManifest read_manifest_json(const std::string& path);

/// Parses a shard "i/N" (0 <= i < N); false when malformed.
bool parse_shard(const std::string& text, int& index, int& count);

/// seeds.csv: "run,seed" for the given runs, atomically.
void write_seeds_csv(const std::string& path, const std::vector<int>& runs,
                     std::uint64_t first_seed);

/// failed.json in a run's result directory: why the run of a method did not finish.
struct RunFailure {
  int run = 0;
  std::uint64_t seed = 0;
  std::string stage;   ///< "simulate" or "run"
  std::string reason;  ///< exit status or signal, and the last stderr line
  /// An external method's last stderr lines (written as "stderr" when there are any).
  std::vector<std::string> stderr_tail;
};
void to_json(io::Json& json, const RunFailure& failure);
void write_failure_json(const std::string& path, const RunFailure& failure);

/// summary.json: one object per method, in the order given, atomically.
void write_summary_json(const std::string& path, const std::vector<MethodSummary>& methods);

/// summary.json read back, methods in file order. The per-scan NEES is not in the file (it is in
/// nees.csv), so `summary.nees` stays empty and `nees_scans` gives its length.
struct StoredSummary {
  MethodSummary summary;
  std::size_t nees_scans = 0;
};
/// One method's object in summary.json (its name is the member's key).
void to_json(io::Json& json, const MethodSummary& summary);
void from_json(const io::JsonObject& json, StoredSummary& stored);
void to_json(io::Json& json, const PairedDifference& paired);
void from_json(const io::JsonObject& json, PairedDifference& paired);
std::vector<StoredSummary> read_summary_json(const std::string& path);

/// errors.csv of a Monte Carlo directory: "method,t_s,runs,mean_m,p05_m,p50_m,p95_m", the spread
/// of the position error over the runs once a second, atomically.
void write_error_spread_csv(const std::string& path, const std::vector<MethodSummary>& methods);

/// error_histogram.csv of a Monte Carlo directory: "method,lower_m,upper_m,fraction", each
/// method's pooled position errors on shared bins, atomically.
void write_error_histogram_csv(const std::string& path,
                               const std::vector<ErrorHistogram>& histograms);

/// nees.csv of a Monte Carlo directory: "method,scan,runs,mean_nees,lower,upper", atomically.
void write_montecarlo_nees_csv(const std::string& path, const std::vector<MethodSummary>& methods);

}  // namespace msislab::results
