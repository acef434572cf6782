// `msislab report OUT.md [--sim DIR] [--real DIR] [--montecarlo DIR ...] [--sweep DIR ...]
// [--sensitivity CSV]`: the results page
// (docs/results.md, written by tools/results.sh) from result folders that `msislab run` and
// `msislab plot` filled and Monte Carlo directories: the paper's Table I on simulated and real
// data, a Monte Carlo consistency table per directory, a table per sweep (its cells' mean errors,
// paired differences, ANEES and linearisation errors), the real result's sensitivity to each
// parameter and the figures, copied beside the page (docs/cli.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "eval/monte_carlo.hpp"
#include "io/montecarlo_files.hpp"
#include "io/results.hpp"
#include "io/sensitivity_csv.hpp"
#include "io/sweep_files.hpp"

namespace msislab::app {

struct ReportOptions {
  std::string out_path;  ///< the Markdown page; its figures go to <stem>/ beside it
  std::string sim_dir;   ///< a folder of results on a simulated dataset (may be empty)
  std::string real_dir;  ///< a folder of results on the real dataset (may be empty)
  /// Monte Carlo directories (may be none): the first is the consistency test of the page, each
  /// further one (another scenario: the failure cases) gets a section of its own.
  std::vector<std::string> montecarlo_dirs;
  /// Sweep directories (may be none), each a section with its sweep.csv as a table.
  std::vector<std::string> sweep_dirs;
  /// The CSV of tools/real_sensitivity.sh (may be empty): the real result's sensitivity section.
  std::string sensitivity_csv;
};

/// One folder of results: each method's metrics and the figures `msislab plot` drew.
struct ResultFolder {
  std::string label;                 ///< "sim" or "real": prefix of its copied figures
  std::string dir;                   ///< as given
  std::string dataset;               ///< the dataset the results were run on (metrics.json)
  std::string scenario;              ///< its name: the prefix of its logs, else its folder's name
  std::vector<RunMetrics> results;   ///< in the order robocentric, worldcentric, deadreckoning,
                                     ///< integration, then any other by name
  std::vector<std::string> figures;  ///< PNG file names in DIR/figures/, sorted
};

struct MonteCarloFolder {
  std::string label;  ///< prefix of its copied figures: "montecarlo", then "montecarlo_<scenario>"
  std::string dir;
  io::MonteCarloManifest manifest;
  std::vector<io::StoredSummary> methods;
  std::vector<std::string> figures;  ///< PNG file names in DIR/figures/, sorted
};

struct SweepFolder {
  std::string dir;  ///< as given; its name titles the section
  io::SweepTable table;
};

struct ResultsReport {
  std::optional<ResultFolder> sim;
  std::optional<ResultFolder> real;
  std::vector<MonteCarloFolder> montecarlo;  ///< in the order given
  std::vector<SweepFolder> sweeps;           ///< in the order given
  std::string sensitivity_source;            ///< the CSV's path as given (empty: no section)
  std::vector<io::SensitivityRow> sensitivity;
  std::string figures_dir_name;  ///< where the page links its figures, relative to it
};

/// Reads a result folder: every subdirectory with a metrics.json, and DIR/figures/*.png (which
/// must exist: `msislab plot DIR` draws them). Throws io::InputError.
ResultFolder read_result_folder(const std::string& dir, const std::string& label);
/// Reads summary.json, montecarlo.json and DIR/figures/*.png; labels it "montecarlo" (the
/// caller renames further folders). Throws io::InputError.
MonteCarloFolder read_montecarlo_folder(const std::string& dir);

/// The page, Markdown (figures linked as <figures_dir_name>/<label>_<file>).
std::string results_markdown(const ResultsReport& report);

struct ReportOutcome {
  std::vector<std::string> figures;  ///< paths of the copied figures
};

/// Reads every input first, then copies the figures into <stem>/ beside the page (replacing the
/// folder whole) and writes the page atomically. Throws io::InputError (nothing written then).
ReportOutcome write_report(const ReportOptions& options);

}  // namespace msislab::app
