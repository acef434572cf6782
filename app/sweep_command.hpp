// `msislab sweep SWEEP.yaml --out DIR [--jobs J] [--shard i/N]` and `msislab sweep merge OUT_DIR
// SHARD_DIR...`: a Monte Carlo directory per cell of a grid (or list) of scenario and SLAM config
// overrides, each resumable and shardable like `montecarlo` (it is `montecarlo`), summarised in
// DIR/sweep.csv (docs/cli.md, docs/formats.md).
#pragma once

#include <string>
#include <vector>

#include "app/montecarlo.hpp"
#include "results/sweep_files.hpp"

namespace msislab::app {

struct SweepOptions {
  std::string sweep_path;
  std::string out_dir;
  int jobs = 0;                ///< runs at once in each cell; 0: one per hardware thread
  std::string shard;           ///< "i/N": in every cell only the runs r with r % N == i
  std::string methods_file{};  ///< external methods (docs/formats.md); empty: none
};

struct SweepOutcome {
  std::size_t cells = 0;
  std::size_t runs = 0;      ///< runs in the cells (of the shard), over every cell
  std::size_t executed = 0;  ///< runs (re)done by this call, over every cell
  std::size_t failed = 0;    ///< runs with a failed method, over every cell
  int interrupted = 0;       ///< the stop request that ended it early, else 0
  results::SweepTable table;
};

/// Reads and checks the sweep file and every cell's inputs (nothing runs before all are valid),
/// locks DIR, refuses a DIR made from another sweep file, then runs the cells in order
/// (DIR/cells/cell_<ccc>, DIR/inputs/cell_<ccc>) and writes DIR/sweep.csv. Throws io::InputError.
SweepOutcome sweep(const SweepOptions& options, const MonteCarloLog& log);

/// Merges shard directories of one sweep file cell by cell into out_dir and writes its sweep.csv.
SweepOutcome merge_sweep(const std::string& out_dir, const std::vector<std::string>& shard_dirs);

}  // namespace msislab::app
