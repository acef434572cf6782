#include "plot/result_figures.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/json.hpp"
#include "results/montecarlo_files.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "stats/chi_square.hpp"

namespace msislab::plot {

namespace fs = std::filesystem;

namespace {

using Row = std::map<std::string, double>;

void put(Row& row, const std::string& key, const std::optional<double>& value) {
  if (value) row[key] = *value;
}

/// metrics.json of a run, and the share of its scans whose NEES lies inside one run's bounds.
Row run_row(const fs::path& dir, std::string& method) {
  const results::StoredMetrics stored = results::read_metrics_json((dir / "metrics.json").string());
  const RunMetrics& m = stored.metrics;
  method = m.method;
  Row row;
  row["runs"] = 1;
  row["mean_error_m"] = m.errors.mean_m;
  row["rmse_m"] = m.errors.rmse_m;
  row["median_error_m"] = m.errors.median_m;
  row["max_error_m"] = m.errors.max_m;
  row["final_error_m"] = m.errors.final_m;
  row["truth_samples"] = static_cast<double>(m.errors.count);
  row["scans"] = m.scans;
  row["matches_accepted"] = m.matches_accepted;
  put(row, "anees", m.anees);
  for (const auto& [name, value] : m.segments) put(row, "segments." + name, value);
  for (const auto& [name, value] : m.diagnostics) row["diagnostics." + name] = value;
  const fs::path nees = dir / "nees.csv";
  if (fs::exists(nees)) {
    const std::vector<results::NeesSample> samples = results::read_nees_csv(nees.string());
    const auto bounds = average_chi2_bounds(1, 3, 0.05);
    const auto inside =
        std::count_if(samples.begin(), samples.end(), [&](const results::NeesSample& s) {
          return s.nees >= bounds.first && s.nees <= bounds.second;
        });
    if (!samples.empty()) {
      row["nees_in_bounds_fraction"] =
          static_cast<double>(inside) / static_cast<double>(samples.size());
    }
  }
  return row;
}

Row montecarlo_row(const results::StoredSummary& stored) {
  const MethodSummary& s = stored.summary;
  Row row;
  row["runs"] = s.runs;
  row["failed"] = s.failed;
  row["missing"] = s.missing;
  put(row, "mean_error_m", s.mean_error_m);
  if (s.mean_error_quantiles_m) {
    row["mean_error_p05_m"] = (*s.mean_error_quantiles_m)[0];
    row["mean_error_p50_m"] = (*s.mean_error_quantiles_m)[1];
    row["mean_error_p95_m"] = (*s.mean_error_quantiles_m)[2];
  }
  put(row, "final_error_m", s.final_error_m);
  put(row, "anees", s.anees);
  put(row, "nees_in_bounds_fraction", s.nees_in_bounds_fraction);
  for (const auto& [name, value] : s.segments) put(row, "segments." + name, value);
  for (const auto& [name, value] : s.diagnostics) row["diagnostics." + name] = value;
  if (s.paired) {
    row["paired_difference.runs"] = s.paired->runs;
    row["paired_difference.mean_m"] = s.paired->mean_m;
    row["paired_difference.sd_m"] = s.paired->sd_m;
    row["paired_difference.ci95_lower_m"] = s.paired->ci95_lower_m;
    row["paired_difference.ci95_upper_m"] = s.paired->ci95_upper_m;
    row["paired_difference.runs_lower"] = s.paired->runs_lower;
    row["paired_difference.runs_not_lower"] = s.paired->runs - s.paired->runs_lower;
  }
  return row;
}

Row sweep_row(const results::SweepRow& r) {
  Row row;
  row["runs"] = r.runs;
  row["failed"] = r.failed;
  put(row, "mean_error_m", r.mean_error_m);
  put(row, "mean_error_p05_m", r.p05_m);
  put(row, "mean_error_p50_m", r.p50_m);
  put(row, "mean_error_p95_m", r.p95_m);
  put(row, "anees", r.anees);
  put(row, "nees_in_bounds_fraction", r.nees_in_bounds_fraction);
  put(row, "paired_difference.mean_m", r.paired_difference_m);
  put(row, "paired_difference.ci95_lower_m", r.paired_ci95_lower_m);
  put(row, "paired_difference.ci95_upper_m", r.paired_ci95_upper_m);
  if (r.paired_runs_lower) row["paired_difference.runs_lower"] = *r.paired_runs_lower;
  put(row, "diagnostics.linearisation_observation", r.linearisation_observation);
  put(row, "diagnostics.linearisation_inversion", r.linearisation_inversion);
  put(row, "diagnostics.linearisation_pose", r.linearisation_pose);
  return row;
}

/// fidelity.json: one row "fidelity", each statistic's real, sim, ratio and ks by its key.
Row fidelity_row(const fs::path& file) {
  const io::Json json = io::read_json_file(file.string());
  const io::JsonObject root(json, file.string());
  Row row;
  const io::Json& rows = root.array("rows");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const io::JsonObject r(rows[i], file.string(), "rows[" + std::to_string(i) + "]");
    const std::string key = r.string("key");
    for (const char* figure : {"real", "sim", "ratio", "ks"}) {
      if (r.has(figure)) put(row, key + "." + figure, r.number_or_null(figure));
    }
  }
  return row;
}

}  // namespace

ResultFigures read_result_figures(const std::string& name, const std::string& path) {
  const fs::path dir(path);
  if (!fs::is_directory(dir)) io::fail_file(path, "not a result folder (no such folder)");
  ResultFigures result{name, path, "", {}};
  if (fs::exists(dir / "summary.json")) {
    result.kind = "montecarlo";
    for (const results::StoredSummary& stored :
         results::read_summary_json((dir / "summary.json").string())) {
      result.rows[stored.summary.method] = montecarlo_row(stored);
    }
  } else if (fs::exists(dir / "sweep.csv")) {
    result.kind = "sweep";
    for (const results::SweepRow& r : results::read_sweep_csv((dir / "sweep.csv").string()).rows) {
      result.rows[sweep_row_key(r.cell, r.method)] = sweep_row(r);
    }
  } else if (fs::exists(dir / "fidelity.json")) {
    result.kind = "fidelity";
    result.rows["fidelity"] = fidelity_row(dir / "fidelity.json");
  } else if (fs::exists(dir / "metrics.json")) {
    result.kind = "run";
    std::string method;
    Row row = run_row(dir, method);
    result.rows[method] = std::move(row);
  } else {
    result.kind = "runs";
    std::vector<fs::path> children;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      if (entry.is_directory() && fs::exists(entry.path() / "metrics.json")) {
        children.push_back(entry.path());
      }
    }
    std::sort(children.begin(), children.end());
    for (const fs::path& child : children) {
      std::string method;
      Row row = run_row(child, method);
      if (!result.rows.emplace(method, std::move(row)).second) {
        io::fail_file(child.string(), "a second run of method '" + method + "' in " + path);
      }
    }
    if (result.rows.empty()) {
      io::fail_file(path,
                    "not a result folder (no metrics.json, summary.json, sweep.csv or "
                    "fidelity.json, nor folders with metrics.json)");
    }
  }
  // Every figure given here must be one an expectations file may name (is_figure_name): a name
  // added to a row above without being added there is a programming error, caught by any test.
  for (const auto& [row_key, row] : result.rows) {
    for (const auto& [figure, value] : row) {
      if (!is_figure_name(figure)) {
        throw std::logic_error("plot/result_figures: figure '" + figure + "' of " + row_key +
                               " is missing from eval/expectations' figure_names()");
      }
    }
  }
  return result;
}

}  // namespace msislab::plot
