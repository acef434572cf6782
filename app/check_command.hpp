// `msislab check EXPECTATIONS.yaml [NAME=]RESULT... [--junit FILE] [--partial]`: compares result
// folders (run, a folder of runs, montecarlo, sweep) with stated expectations, prints a table,
// writes JUnit XML, and exits 1 when any expectation is missed (docs/cli.md, "msislab check").
#pragma once

#include <string>
#include <vector>

#include "eval/expectations.hpp"

namespace msislab::app {

struct CheckOptions {
  std::string expectations_path;
  std::vector<std::string> results;  ///< NAME=PATH or PATH (named after its folder)
  std::string junit_path;
  bool partial = false;  ///< expectations on results not given are not checked (not a miss)
};

/// Every expectation's outcome, quotes included, in file order.
std::vector<CheckOutcome> run_check(const CheckOptions& options);

}  // namespace msislab::app
