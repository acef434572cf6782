#include "eval/monte_carlo.hpp"

#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "stats/chi_square.hpp"
#include "stats/sample_statistics.hpp"

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

// Per time the runs sampled (errors_at: t_s -> the runs' errors then), in time order, the
// spread of the errors.
std::vector<ErrorSpread> error_spread(const std::map<double, std::vector<double>>& errors_at) {
  std::vector<ErrorSpread> spread;
  for (const auto& [t_s, errors] : errors_at) {
    double sum = 0.0;
    for (const double e : errors) sum += e;
    spread.push_back({t_s, static_cast<int>(errors.size()),
                      sum / static_cast<double>(errors.size()), quantile(errors, 0.05),
                      quantile(errors, 0.5), quantile(errors, 0.95)});
  }
  return spread;
}

// The 5, 50 and 95 % quantiles of the present mean errors; nullopt when none.
std::optional<std::array<double, 3>> mean_error_quantiles(
    const std::vector<std::optional<double>>& mean_errors) {
  std::vector<double> finished_means;
  for (const std::optional<double>& m : mean_errors) {
    if (m) finished_means.push_back(*m);
  }
  if (finished_means.empty()) return std::nullopt;
  return std::array<double, 3>{quantile(finished_means, 0.05), quantile(finished_means, 0.5),
                               quantile(finished_means, 0.95)};
}

// Per segment name, in order of first appearance, the mean over the finished runs of the
// segment's mean error.
std::vector<std::pair<std::string, std::optional<double>>> segment_means(
    const std::vector<MonteCarloRun>& runs) {
  std::vector<std::pair<std::string, std::optional<double>>> segments;
  for (const std::string& name : segment_names(runs)) {
    std::vector<std::optional<double>> means;
    for (const MonteCarloRun& run : runs) {
      if (!run.metrics) continue;
      for (const auto& [segment, mean] : run.metrics->segments) {
        if (segment == name) means.push_back(mean);
      }
    }
    segments.emplace_back(name, mean_present(means));
  }
  return segments;
}

// Per diagnostic name, in order of first appearance, the mean over the finished runs with a
// finite value.
std::vector<std::pair<std::string, double>> diagnostic_means(
    const std::vector<MonteCarloRun>& runs) {
  std::vector<std::pair<std::string, std::pair<double, int>>> diagnostics;  // sum, count
  for (const MonteCarloRun& run : runs) {
    if (!run.metrics) continue;
    for (const auto& [name, value] : run.metrics->diagnostics) {
      if (!std::isfinite(value)) continue;
      // C++17 lambdas cannot capture a structured binding (clang rejects it): a plain reference.
      const std::string& key = name;
      auto it = std::find_if(diagnostics.begin(), diagnostics.end(),
                             [&](const auto& d) { return d.first == key; });
      if (it == diagnostics.end()) it = diagnostics.insert(diagnostics.end(), {name, {0.0, 0}});
      it->second.first += value;
      ++it->second.second;
    }
  }
  std::vector<std::pair<std::string, double>> means;
  for (const auto& [name, sum_count] : diagnostics) {
    means.emplace_back(name, sum_count.first / sum_count.second);
  }
  return means;
}

}  // namespace

MethodSummary summarise_runs(const std::string& method, const std::vector<MonteCarloRun>& runs) {
  MethodSummary summary;
  summary.method = method;
  std::vector<std::optional<double>> mean_errors, final_errors;
  std::vector<std::vector<double>> nees_by_run;
  std::map<double, std::vector<double>> errors_at;  // t_s -> the runs' errors then
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
    if (std::isfinite(run.metrics->errors.mean_m)) {
      summary.run_mean_errors_m.emplace_back(run.index, run.metrics->errors.mean_m);
    }
    final_errors.push_back(run.metrics->errors.final_m);
    if (std::isfinite(run.metrics->runtime_s)) summary.runtime_s += run.metrics->runtime_s;
    for (const ErrorSample& e : run.errors) {
      errors_at[e.t_s].push_back(e.error_m);
      summary.pooled_errors_m.push_back(e.error_m);
    }
    if (run.nees.empty()) continue;
    nees_by_run.push_back(run.nees);
    for (const double v : run.nees) nees_sum += v;
    nees_count += run.nees.size();
  }
  summary.error_spread = error_spread(errors_at);
  summary.mean_error_m = mean_present(mean_errors);
  summary.mean_error_quantiles_m = mean_error_quantiles(mean_errors);
  summary.final_error_m = mean_present(final_errors);
  if (nees_count > 0) summary.anees = nees_sum / static_cast<double>(nees_count);
  summary.nees = average_nees_over_runs(nees_by_run);
  summary.nees_in_bounds_fraction = fraction_inside(summary.nees);
  summary.segments = segment_means(runs);
  summary.diagnostics = diagnostic_means(runs);
  return summary;
}

std::optional<PairedDifference> paired_difference(const MethodSummary& method,
                                                  const MethodSummary& reference) {
  const std::map<int, double> reference_by_run(reference.run_mean_errors_m.begin(),
                                               reference.run_mean_errors_m.end());
  std::vector<double> d;
  PairedDifference out;
  out.reference = reference.method;
  for (const auto& [run, error_m] : method.run_mean_errors_m) {
    const auto it = reference_by_run.find(run);
    if (it == reference_by_run.end()) continue;
    d.push_back(error_m - it->second);
    out.runs_lower += error_m < it->second;
  }
  if (d.size() < 2) return std::nullopt;
  const double n = static_cast<double>(d.size());
  double sum = 0.0;
  for (const double v : d) sum += v;
  out.mean_m = sum / n;
  double squares = 0.0;
  for (const double v : d) squares += (v - out.mean_m) * (v - out.mean_m);
  out.sd_m = std::sqrt(squares / (n - 1.0));
  const double t = boost::math::quantile(boost::math::students_t(n - 1.0), 0.975);
  const double half_width = t * out.sd_m / std::sqrt(n);
  out.runs = static_cast<int>(d.size());
  out.ci95_lower_m = out.mean_m - half_width;
  out.ci95_upper_m = out.mean_m + half_width;
  return out;
}

std::vector<ErrorHistogram> error_histograms(const std::vector<MethodSummary>& methods, int bins) {
  double largest = 0.0;
  for (const MethodSummary& m : methods) {
    for (const double e : m.pooled_errors_m) largest = std::max(largest, e);
  }
  std::vector<ErrorHistogram> histograms;
  if (bins < 1 || !(largest > 0.0)) return histograms;
  const double width = largest / bins;
  for (const MethodSummary& m : methods) {
    if (m.pooled_errors_m.empty()) continue;
    ErrorHistogram h;
    h.method = m.method;
    for (int b = 0; b <= bins; ++b) h.edges_m.push_back(b == bins ? largest : b * width);
    std::vector<std::size_t> counts(static_cast<std::size_t>(bins), 0);
    for (const double e : m.pooled_errors_m) {
      const auto b = static_cast<std::size_t>(std::clamp(static_cast<int>(e / width), 0, bins - 1));
      ++counts[b];
    }
    for (const std::size_t c : counts) {
      h.fractions.push_back(static_cast<double>(c) / static_cast<double>(m.pooled_errors_m.size()));
    }
    histograms.push_back(std::move(h));
  }
  return histograms;
}

}  // namespace msislab
