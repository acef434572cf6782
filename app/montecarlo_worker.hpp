// The worker process of one Monte Carlo run: it simulates the run into memory, runs the pending
// methods on that dataset (writing it to disk only for an external method or with
// --keep-datasets), and puts each method's result in place or records its failure. The caller
// (app/montecarlo_runs) forks one per run.
#pragma once

#include <string>
#include <vector>

#include "app/montecarlo_runs.hpp"
#include "results/montecarlo_files.hpp"

namespace msislab::app {

/// Worker process of run r: simulates into memory, runs the pending methods on the dataset and
/// puts each method's result (or its failed.json) in place. Returns the process's exit status.
int execute_run(const RunContext& ctx, int run, const std::vector<std::string>& pending);

/// Records that a method did not finish run r: a run directory holding only failed.json.
void record_failure(const std::string& dir, const std::string& method,
                    const results::RunFailure& failure);

/// DIR/scratch/run_<rrrr><suffix>: a worker's scratch file.
std::string scratch_file(const std::string& dir, int run, const char* suffix);

/// The last line of the worker's stage notes ("simulate" or "run"); "simulate" when there is none.
std::string crashed_stage(const std::string& dir, int run);

}  // namespace msislab::app
