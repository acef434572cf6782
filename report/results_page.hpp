// The results page of `msislab report` (docs/results.md): the result folders that `msislab run`
// and `msislab plot` filled and the Monte Carlo and sweep directories, read back, and the page's
// Markdown from them: the paper's Table I on simulated and real data, a Monte Carlo consistency
// table per directory, a table per sweep (its cells' mean errors, paired differences, ANEES and
// linearisation errors), the real result's sensitivity to each parameter and the figure lists.
// app/report_command copies the figures and writes the page.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "eval/monte_carlo.hpp"
#include "io/sensitivity_csv.hpp"
#include "report/method_styles.hpp"
#include "results/montecarlo_files.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"

namespace msislab::report {

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
  results::MonteCarloManifest manifest;
  std::vector<results::StoredSummary> methods;
  std::vector<std::string> figures;  ///< PNG file names in DIR/figures/, sorted
};

struct SweepFolder {
  std::string dir;  ///< as given; its name titles the section
  results::SweepTable table;
};

struct ResultsReport {
  std::optional<ResultFolder> sim;
  std::optional<ResultFolder> real;
  std::vector<MonteCarloFolder> montecarlo;  ///< in the order given
  std::vector<SweepFolder> sweeps;           ///< in the order given
  std::string sensitivity_source;            ///< the CSV's path as given (empty: no section)
  std::vector<io::SensitivityRow> sensitivity;
  std::string figures_dir_name;  ///< where the page links its figures, relative to it
  MethodStyles styles;           ///< the methods' titles
};

/// Reads a result folder: every subdirectory with a metrics.json, and DIR/figures/*.png (which
/// must exist: `msislab plot DIR` draws them). Throws io::InputError.
/// Its methods in the order of `styles`.
ResultFolder read_result_folder(const MethodStyles& styles, const std::string& dir,
                                const std::string& label);
/// Reads summary.json, montecarlo.json and DIR/figures/*.png; labels it "montecarlo" (the
/// caller renames further folders). Throws io::InputError.
MonteCarloFolder read_montecarlo_folder(const std::string& dir);

/// The page, Markdown (figures linked as <figures_dir_name>/<label>_<file>).
std::string results_markdown(const ResultsReport& report);

}  // namespace msislab::report
