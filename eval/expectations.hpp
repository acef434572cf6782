// Stated expectations on the figures of result folders, for `msislab check` (docs/cli.md): a
// figure at most or at least a value, equal to a value within a tolerance, an ANEES inside the
// chi-square bounds of its run count, one method's figure below another's. The figures come
// flattened (io/result_figures): per row (a method, and a sweep's cell) a dotted key -> number.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace msislab {

/// The figures of one result folder: rows keyed by method (sweep rows by "cell N/method"), each a
/// map from a dotted key ("mean_error_m", "segments.exit", "paired_difference.ci95_upper_m") to
/// its value; a null figure is absent.
struct ResultFigures {
  std::string name;  ///< how expectations name it (NAME=PATH, else the folder's name)
  std::string path;
  std::string kind;  ///< "run", "runs" (a folder of run folders), "montecarlo" or "sweep"
  std::map<std::string, std::map<std::string, double>> rows;
};

/// Whether a result of some kind can hold a figure of this name: one of figure_names(), a
/// segment's or a diagnostic's ("segments.NAME", "diagnostics.NAME"), or a fidelity statistic's
/// ("KEY.real", "KEY.sim", "KEY.ratio", "KEY.ks"). A name no result defines is bad input in an
/// expectations file, not a miss.
bool is_figure_name(const std::string& name);

/// The figure names that do not depend on a run's segments, diagnostics or a fidelity table: every
/// one that a run, a folder of runs, a Monte Carlo or a sweep can give (plot/result_figures).
const std::vector<std::string>& figure_names();

/// The row key of a sweep's cell and method.
std::string sweep_row_key(int cell, const std::string& method);

/// One expectation, as read from an expectations file (io/expectations_yaml).
struct Expectation {
  std::string name;         ///< shown in the table and as the JUnit test case
  std::string location;     ///< "FILE:LINE" of its entry
  std::string result;       ///< the result it reads; empty when only one result is given
  std::string method;       ///< the row; empty for a result with a single row
  std::optional<int> cell;  ///< a sweep's cell
  std::string metric = "mean_error_m";
  std::optional<double> at_most;
  std::optional<double> at_least;
  std::optional<double> equals;
  double tolerance = 0.0;        ///< with equals: |value - equals| <= tolerance
  std::string equals_text;       ///< equals as written (its decimals format the quote)
  bool anees_in_bounds = false;  ///< metric anees inside average_chi2_bounds(runs, 3, 0.05)
  std::string below;             ///< another method of the same result: metric below its metric
  /// With equals: a file (relative to the expectations file) that quotes the figure, and the
  /// text around it, "{}" standing for equals_text; the file must contain it (white space folded).
  std::string quote_file;
  std::string quote_text;
};

/// The outcome of one expectation.
struct CheckOutcome {
  std::string name;
  bool met = false;
  bool checked = true;   ///< false when its result was not given (msislab check --partial)
  std::string value;     ///< what was found, e.g. "2.787"
  std::string expected;  ///< e.g. "<= 3", "2.84 +- 0.005", "in [2.36, 3.72]"
  std::string why;       ///< for a miss: one line
};

/// Checks one expectation against the results given. A missing result, row or figure is a miss
/// that says what is missing (a result not among `results` with `partial` is not checked).
CheckOutcome check_expectation(const Expectation& expectation,
                               const std::vector<ResultFigures>& results, bool partial = false);

/// The quote of an expectation with equals and a quote: "{}" replaced by equals_text.
std::string quoted_text(const Expectation& expectation);

/// The text with every run of white space (spaces, tabs, line breaks) one space, none at the ends.
std::string fold_white_space(const std::string& text);

/// Whether `page` contains `quote` when every run of white space in both counts as one space.
bool page_quotes(const std::string& page, const std::string& quote);

}  // namespace msislab
