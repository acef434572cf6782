// The layout of a Monte Carlo directory (docs/formats.md) shared by `montecarlo` and its merge:
// the run directories, the header files (scenario.yaml, config.yaml, montecarlo.json) and the
// summary files computed from the run directories alone, so that a merge of shards writes the
// same bytes as one full run.
#pragma once

#include <string>
#include <vector>

#include "eval/monte_carlo.hpp"
#include "results/montecarlo_files.hpp"

namespace msislab::app {

/// "run_0042".
std::string run_name(int run);
/// DIR/runs/<method>/run_<rrrr>: the result directory of run r of a method.
std::string run_dir(const std::string& dir, const std::string& method, int run);

/// The run indices of the manifest's shard, in increasing order.
std::vector<int> runs_of(const results::MonteCarloManifest& manifest);

/// A digest of the msislab executable's bytes (FNV-1a, 64 bits, hex): another build, with other
/// defaults or code, has another digest. InputError when the file cannot be read.
std::string executable_digest(const std::string& executable_path);

/// The bytes of the files a Monte Carlo directory keeps copies of.
struct DirectoryInputs {
  std::string scenario_text;
  std::string config_text;   ///< when the manifest has_config
  std::string methods_text;  ///< when the manifest has_methods_file
};

/// InputError unless dir is new or holds runs made from the same scenario, config and methods
/// file bytes by the executable with this digest.
void check_resumable(const std::string& dir, const results::MonteCarloManifest& manifest,
                     const DirectoryInputs& inputs, const std::string& scenario_path);

/// Creates dir and writes scenario.yaml, config.yaml (when has_config), methods.yaml (when
/// has_methods_file) and montecarlo.json.
void write_directory_header(const std::string& dir, const results::MonteCarloManifest& manifest,
                            const DirectoryInputs& inputs);

/// Summarises the given runs of every method from their run directories and writes summary.json,
/// nees.csv and seeds.csv.
std::vector<MethodSummary> write_summary_files(const std::string& dir,
                                               const results::MonteCarloManifest& manifest,
                                               const std::vector<int>& runs);

/// How many of the runs have a failed.json for at least one method.
std::size_t failed_runs(const std::string& dir, const std::vector<std::string>& methods,
                        const std::vector<int>& runs);

}  // namespace msislab::app
