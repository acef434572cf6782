// `msislab report OUT.md [--sim DIR] [--real DIR] [--montecarlo DIR ...] [--sweep DIR ...]
// [--sensitivity CSV]`: the results page
// (docs/results.md, written by tools/results.sh) from result folders that `msislab run` and
// `msislab plot` filled and Monte Carlo directories: the paper's Table I on simulated and real
// data, a Monte Carlo consistency table per directory, a table per sweep (its cells' mean errors,
// paired differences, ANEES and linearisation errors), the real result's sensitivity to each
// parameter and the figures, copied beside the page (docs/cli.md). The folders are read and the
// page is built by report/results_page.hpp; this command checks the outputs, copies the figures
// and writes the page.
#pragma once

#include <string>
#include <vector>

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
  /// A methods file (may be empty): the titles, colours and line styles of external methods.
  std::string methods_file{};
};

struct ReportOutcome {
  std::vector<std::string> figures;  ///< paths of the copied figures
};

/// Reads every input first, then copies the figures into <stem>/ beside the page (replacing the
/// folder whole) and writes the page atomically. Throws io::InputError (nothing written then).
ReportOutcome write_report(const ReportOptions& options);

}  // namespace msislab::app
