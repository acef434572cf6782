// The figures of a result folder flattened for `msislab check` (eval/expectations): a run's
// metrics.json, a folder of such run folders (one row per method), a Monte Carlo directory's
// summary.json or a sweep's sweep.csv, each as rows of dotted key -> number (docs/cli.md).
#pragma once

#include <string>

#include "eval/expectations.hpp"

namespace msislab::plot {

/// Reads the result folder at `path` (kind told by what it holds); `name` is how expectations
/// refer to it. InputError naming the folder when it holds no result, or two runs of one method.
ResultFigures read_result_figures(const std::string& name, const std::string& path);

}  // namespace msislab::plot
