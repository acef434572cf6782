// `msislab simulate SCENARIO.yaml --out DIR [--seed N] [--threads T]`: renders a synthetic dataset.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace msislab::app {

struct SimulateOptions {
  std::string scenario_path;
  std::string out_dir;
  std::optional<std::uint64_t> seed;  ///< overrides the scenario's seed
  int threads = 0;                    ///< 0: one per hardware thread
  bool force = false;                 ///< replace a folder msislab did not write
};

struct SimulateSummary {
  std::size_t beams = 0;
  std::size_t dvl_samples = 0;
  double duration_s = 0.0;  ///< simulated time
  double render_s = 0.0;    ///< wall time of the simulation itself
  double total_s = 0.0;     ///< wall time including loading and writing
  std::size_t rays_per_beam = 0;
};

/// Reads and checks the scenario and mesh, simulates, and writes the dataset directory.
/// Throws io::InputError on bad input.
SimulateSummary simulate(const SimulateOptions& options);

}  // namespace msislab::app
