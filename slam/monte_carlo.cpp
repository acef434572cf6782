#include "slam/monte_carlo.hpp"

#include <algorithm>
#include <cmath>

#include "slam/scan_matching.hpp"

namespace msislab {

std::vector<AveragedNees> average_nees_over_runs(
    const std::vector<std::vector<double>>& nees_by_run, int dof, double alpha) {
  std::size_t steps = 0;
  for (const std::vector<double>& run : nees_by_run) steps = std::max(steps, run.size());
  std::vector<AveragedNees> averaged(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    int runs = 0;
    for (const std::vector<double>& run : nees_by_run) {
      if (k >= run.size()) continue;
      sum += run[k];
      ++runs;
    }
    const auto [lower, upper] = average_chi2_bounds(runs, dof, alpha);
    averaged[k] = {runs, sum / runs, lower, upper};
  }
  return averaged;
}

std::optional<double> fraction_inside(const std::vector<AveragedNees>& steps) {
  if (steps.empty()) return std::nullopt;
  const auto inside =
      std::count_if(steps.begin(), steps.end(), [](const AveragedNees& s) { return s.inside(); });
  return static_cast<double>(inside) / static_cast<double>(steps.size());
}

namespace {

// Mean of the present values; nullopt when none.
std::optional<double> mean_present(const std::vector<std::optional<double>>& values) {
  double sum = 0.0;
  int count = 0;
  for (const std::optional<double>& v : values) {
    if (!v) continue;
    sum += *v;
    ++count;
  }
  if (count == 0) return std::nullopt;
  return sum / count;
}

// Segment names in order of first appearance over the runs.
std::vector<std::string> segment_names(const std::vector<MonteCarloRun>& runs) {
  std::vector<std::string> names;
  for (const MonteCarloRun& run : runs) {
    if (!run.metrics) continue;
    for (const auto& [name, mean] : run.metrics->segments) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }
  return names;
}

}  // namespace

MethodSummary summarise_runs(const std::string& method, const std::vector<MonteCarloRun>& runs) {
  MethodSummary summary;
  summary.method = method;
  std::vector<std::optional<double>> mean_errors, final_errors;
  std::vector<std::vector<double>> nees_by_run;
  double nees_sum = 0.0;
  std::size_t nees_count = 0;
  for (const MonteCarloRun& run : runs) {
    if (!run.metrics) {
      if (run.failed) summary.failed_runs.push_back(run.index);
      summary.failed += run.failed;
      summary.missing += !run.failed;
      continue;
    }
    ++summary.runs;
    mean_errors.push_back(run.metrics->errors.mean_m);
    final_errors.push_back(run.metrics->errors.final_m);
    if (std::isfinite(run.metrics->runtime_s)) summary.runtime_s += run.metrics->runtime_s;
    if (run.nees.empty()) continue;
    nees_by_run.push_back(run.nees);
    for (const double v : run.nees) nees_sum += v;
    nees_count += run.nees.size();
  }
  summary.mean_error_m = mean_present(mean_errors);
  summary.final_error_m = mean_present(final_errors);
  if (nees_count > 0) summary.anees = nees_sum / static_cast<double>(nees_count);
  summary.nees = average_nees_over_runs(nees_by_run);
  summary.nees_in_bounds_fraction = fraction_inside(summary.nees);
  for (const std::string& name : segment_names(runs)) {
    std::vector<std::optional<double>> means;
    for (const MonteCarloRun& run : runs) {
      if (!run.metrics) continue;
      for (const auto& [segment, mean] : run.metrics->segments) {
        if (segment == name) means.push_back(mean);
      }
    }
    summary.segments.emplace_back(name, mean_present(means));
  }
  return summary;
}

}  // namespace msislab
