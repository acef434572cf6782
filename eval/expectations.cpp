#include "eval/expectations.hpp"

#include <cmath>
#include <cstdio>

#include "stats/chi_square.hpp"

namespace msislab {

namespace {

std::string number_text(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

CheckOutcome miss(CheckOutcome outcome, const std::string& why) {
  outcome.met = false;
  outcome.why = why;
  return outcome;
}

const ResultFigures* find_result(const std::vector<ResultFigures>& results,
                                 const std::string& name) {
  if (name.empty()) return results.size() == 1 ? &results.front() : nullptr;
  for (const ResultFigures& result : results) {
    if (result.name == name) return &result;
  }
  return nullptr;
}

/// The row an expectation reads: its method (and cell), or a result's only row.
const std::map<std::string, double>* find_row(const ResultFigures& result, const Expectation& e,
                                              std::string& key) {
  if (e.method.empty() && !e.cell) {
    if (result.rows.size() != 1) return nullptr;
    key = result.rows.begin()->first;
    return &result.rows.begin()->second;
  }
  key = e.cell ? sweep_row_key(*e.cell, e.method) : e.method;
  const auto row = result.rows.find(key);
  return row == result.rows.end() ? nullptr : &row->second;
}

std::optional<double> figure(const std::map<std::string, double>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end()) return std::nullopt;
  return it->second;
}

std::string row_names(const ResultFigures& result) {
  std::string names;
  for (const auto& [key, row] : result.rows) names += (names.empty() ? "" : ", ") + key;
  return names.empty() ? "none" : names;
}

/// Applies e's bounds to value: each appended to expected, met cleared by one that fails. The
/// error when the figure of the method it must stay below is missing.
std::optional<std::string> apply_bounds(const Expectation& e, const ResultFigures& result,
                                        const std::map<std::string, double>& row,
                                        const std::string& metric, double value, bool& met,
                                        std::string& expected) {
  const auto require = [&](bool holds, const std::string& what) {
    expected += (expected.empty() ? "" : ", ") + what;
    if (!holds) met = false;
  };
  if (e.at_most) require(value <= *e.at_most, "<= " + number_text(*e.at_most));
  if (e.at_least) require(value >= *e.at_least, ">= " + number_text(*e.at_least));
  if (e.equals) {
    require(std::abs(value - *e.equals) <= e.tolerance,
            number_text(*e.equals) + " +- " + number_text(e.tolerance));
  }
  if (e.anees_in_bounds) {
    const int runs = static_cast<int>(figure(row, "runs").value_or(1.0));
    const auto [lower, upper] = average_chi2_bounds(std::max(runs, 1), 3, 0.05);
    require(value >= lower && value <= upper, "in [" + number_text(lower) + ", " +
                                                  number_text(upper) + "] (" +
                                                  std::to_string(runs) + " runs)");
  }
  if (!e.below.empty()) {
    Expectation other = e;
    other.method = e.below;
    std::string other_key;
    const std::map<std::string, double>* other_row = find_row(result, other, other_key);
    const std::optional<double> other_value = other_row ? figure(*other_row, metric) : std::nullopt;
    if (!other_value) {
      return result.path + ": no figure '" + metric + "' of '" + other_key +
             "' to compare with (rows: " + row_names(result) + ")";
    }
    require(value < *other_value, "< " + number_text(*other_value) + " (" + e.below + ")");
  }
  return std::nullopt;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.size() > prefix.size() && text.compare(0, prefix.size(), prefix) == 0;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() > suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

const std::vector<std::string>& figure_names() {
  static const std::vector<std::string> names = {"runs",
                                                 "failed",
                                                 "missing",
                                                 "scans",
                                                 "matches_accepted",
                                                 "truth_samples",
                                                 "mean_error_m",
                                                 "rmse_m",
                                                 "median_error_m",
                                                 "max_error_m",
                                                 "final_error_m",
                                                 "mean_error_p05_m",
                                                 "mean_error_p50_m",
                                                 "mean_error_p95_m",
                                                 "anees",
                                                 "nees_in_bounds_fraction",
                                                 "paired_difference.runs",
                                                 "paired_difference.mean_m",
                                                 "paired_difference.sd_m",
                                                 "paired_difference.ci95_lower_m",
                                                 "paired_difference.ci95_upper_m",
                                                 "paired_difference.runs_lower",
                                                 "paired_difference.runs_not_lower"};
  return names;
}

bool is_figure_name(const std::string& name) {
  for (const std::string& known : figure_names()) {
    if (name == known) return true;
  }
  if (starts_with(name, "segments.") || starts_with(name, "diagnostics.")) return true;
  for (const char* statistic : {".real", ".sim", ".ratio", ".ks"}) {
    if (ends_with(name, statistic)) return true;
  }
  return false;
}

std::string sweep_row_key(int cell, const std::string& method) {
  return "cell " + std::to_string(cell) + "/" + method;
}

std::string quoted_text(const Expectation& e) {
  std::string text = e.quote_text;
  const std::size_t at = text.find("{}");
  if (at != std::string::npos) text.replace(at, 2, e.equals_text);
  return text;
}

std::string fold_white_space(const std::string& text) {
  std::string folded;
  bool space = false;
  for (const char ch : text) {
    const bool blank = ch == ' ' || ch == '\n' || ch == '\t' || ch == '\r';
    if (blank) {
      space = !folded.empty();
    } else {
      if (space) folded += ' ';
      folded += ch;
      space = false;
    }
  }
  return folded;
}

bool page_quotes(const std::string& page, const std::string& quote) {
  return fold_white_space(page).find(fold_white_space(quote)) != std::string::npos;
}

CheckOutcome check_expectation(const Expectation& e, const std::vector<ResultFigures>& results,
                               bool partial) {
  CheckOutcome outcome;
  outcome.name = e.name;
  const ResultFigures* result = find_result(results, e.result);
  if (result == nullptr) {
    if (partial && !e.result.empty()) {
      outcome.checked = false;
      outcome.met = true;
      return outcome;
    }
    return miss(outcome, e.result.empty()
                             ? "no result named: give it as 'result:' (several results given)"
                             : "result '" + e.result + "' was not given");
  }
  std::string row_key;
  const std::map<std::string, double>* row = find_row(*result, e, row_key);
  if (row == nullptr) {
    return miss(outcome,
                result->path + ": no row " +
                    (e.method.empty()
                         ? std::string("chosen (give 'method:')")
                         : "'" + (e.cell ? sweep_row_key(*e.cell, e.method) : e.method) + "'") +
                    " (rows: " + row_names(*result) + ")");
  }
  const std::string metric = e.anees_in_bounds ? "anees" : e.metric;
  const std::optional<double> value = figure(*row, metric);
  if (!value)
    return miss(outcome, result->path + ": " + row_key + " has no figure '" + metric + "'");
  outcome.value = number_text(*value);
  outcome.met = true;
  std::string expected;
  if (const std::optional<std::string> error =
          apply_bounds(e, *result, *row, metric, *value, outcome.met, expected)) {
    return miss(outcome, *error);
  }
  outcome.expected = expected;
  if (!outcome.met)
    outcome.why = row_key + " " + metric + " = " + outcome.value + ", expected " + expected;
  return outcome;
}

}  // namespace msislab
