// Looking up a Monte Carlo outcome's, or one run's, figures in the end-to-end tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "app/montecarlo.hpp"
#include "eval/evaluation.hpp"

namespace msislab::app::testing_lookup {

/// The summary of `method`; throws when the outcome has none.
inline const MethodSummary& find(const MonteCarloOutcome& outcome, const std::string& method) {
  for (const MethodSummary& s : outcome.summary) {
    if (s.method == method) return s;
  }
  throw std::runtime_error("no summary for " + method);
}

/// The mean error over the runs in segment `name`, m; NaN when it has none.
inline double segment(const MethodSummary& s, const std::string& name) {
  for (const auto& [segment_name, value] : s.segments) {
    if (segment_name == name) return value.value_or(NAN);
  }
  return NAN;
}

/// A run's metrics.json diagnostic `name`; a test failure and NaN when it has none.
inline double diagnostic(const RunMetrics& m, const std::string& name) {
  for (const auto& [key, value] : m.diagnostics) {
    if (key == name) return value;
  }
  ADD_FAILURE() << m.method << ": no diagnostic " << name;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace msislab::app::testing_lookup
