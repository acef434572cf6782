#include "app/check_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>

#include "app/cli.hpp"
#include "io/input_error.hpp"
#include "io/junit_xml.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "plot/result_figures.hpp"
#include "settings/expectations_yaml.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// NAME=PATH, or PATH named after its folder.
std::pair<std::string, std::string> named_result(const std::string& argument) {
  const std::size_t eq = argument.find('=');
  if (eq != std::string::npos && eq > 0 && argument.find('/') > eq) {
    return {argument.substr(0, eq), argument.substr(eq + 1)};
  }
  const fs::path path = fs::path(argument).lexically_normal();
  const std::string name = (path.filename().empty() ? path.parent_path() : path).filename();
  return {name, argument};
}

std::vector<ResultFigures> read_results(const CheckOptions& options,
                                        const std::vector<Expectation>& expectations) {
  std::vector<ResultFigures> results;
  std::set<std::string> names;
  for (const std::string& argument : options.results) {
    const auto [name, path] = named_result(argument);
    if (!names.insert(name).second) {
      throw io::InputError("check: two results named '" + name + "' (name them NAME=PATH)");
    }
    results.push_back(plot::read_result_figures(name, path));
  }
  if (options.partial) return results;
  for (const Expectation& e : expectations) {
    if (!e.result.empty() && names.count(e.result) == 0) {
      std::string given;
      for (const std::string& name : names) given += (given.empty() ? "" : ", ") + name;
      throw io::InputError(e.location + ": result '" + e.result +
                           "' was not given (given: " + (given.empty() ? "none" : given) +
                           "; name one NAME=PATH, or check the rest with --partial)");
    }
  }
  return results;
}

/// The quote of an expectation: the file it names (beside the expectations file) holds it.
void check_quote(const Expectation& e, const std::string& expectations_path,
                 CheckOutcome& outcome) {
  if (e.quote_file.empty()) return;
  const fs::path page = fs::path(expectations_path).parent_path() / e.quote_file;
  if (!fs::is_regular_file(page)) {
    throw io::InputError(e.location + ": quote.file '" + e.quote_file + "': no such file (" +
                         page.string() + ")");
  }
  if (page_quotes(io::read_whole_file(page.string()), quoted_text(e))) return;
  outcome.met = false;
  outcome.checked = true;  // a quote is checked even when its result was not given
  outcome.why += std::string(outcome.why.empty() ? "" : "; ") + e.quote_file +
                 " does not quote \"" + quoted_text(e) + "\"";
}

void print_table(const std::vector<CheckOutcome>& outcomes) {
  std::size_t width = 11;
  for (const CheckOutcome& o : outcomes) width = std::max(width, o.name.size());
  std::cout << std::left << std::setw(6) << "" << std::setw(static_cast<int>(width) + 2)
            << "expectation" << std::setw(14) << "value"
            << "expected\n";
  for (const CheckOutcome& o : outcomes) {
    const char* status = !o.checked ? "skip" : o.met ? "ok" : "MISS";
    std::cout << std::setw(6) << status << std::setw(static_cast<int>(width) + 2) << o.name
              << std::setw(14) << (o.value.empty() ? "-" : o.value) << o.expected << "\n";
  }
}

}  // namespace

std::vector<CheckOutcome> run_check(const CheckOptions& options) {
  const std::vector<Expectation> expectations =
      settings::read_expectations_yaml(options.expectations_path);
  if (options.results.empty() && !options.partial) {
    throw io::InputError("check: no result given (RESULT..., or --partial to check quotes only)");
  }
  if (!options.junit_path.empty()) {
    std::vector<std::string> inputs = options.results;
    inputs.push_back(options.expectations_path);
    io::check_output_file({options.junit_path, "junit report", "check", inputs, false},
                          io::junit_written_by_msislab);
  }
  const std::vector<ResultFigures> results = read_results(options, expectations);
  std::vector<CheckOutcome> outcomes;
  for (const Expectation& e : expectations) {
    CheckOutcome outcome = check_expectation(e, results, options.partial);
    check_quote(e, options.expectations_path, outcome);
    outcomes.push_back(std::move(outcome));
  }
  if (!options.junit_path.empty()) {
    std::vector<io::JunitCase> cases;
    for (const CheckOutcome& o : outcomes) {
      cases.push_back({o.name, fs::path(options.expectations_path).filename().string(),
                       o.met ? "" : o.why, !o.checked});
    }
    io::write_junit_xml(options.junit_path, "msislab check", cases);
  }
  return outcomes;
}

void add_check_command(CLI::App& app, CommandLine& line) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Compare result folders (run, montecarlo, sweep) with stated expectations; exit 1 when any "
      "is missed");
  check->add_option("EXPECTATIONS", options->expectations_path, "Expectations YAML")->required();
  check->add_option("RESULT", options->results,
                    "Result folders, each PATH or NAME=PATH (the name expectations use)");
  check->add_option("--junit", options->junit_path, "Also write JUnit XML to FILE")
      ->type_name("FILE");
  check->add_flag("--partial", options->partial,
                  "Expectations on results not given are listed, not checked (not a miss)");
  check->callback([options, &line] {
    const std::vector<CheckOutcome> outcomes = run_check(*options);
    print_table(outcomes);
    int missed = 0;
    int unchecked = 0;
    for (const CheckOutcome& o : outcomes) {
      if (!o.checked) ++unchecked;
      if (o.met) continue;
      ++missed;
      std::cerr << "msislab check: MISS " << o.name << ": " << o.why << "\n";
    }
    std::cout << "check: " << outcomes.size() - missed - unchecked << " of " << outcomes.size()
              << " expectations met, " << missed << " missed";
    if (unchecked > 0) std::cout << ", " << unchecked << " not checked (--partial)";
    std::cout << "\n";
    if (!options->junit_path.empty()) std::cout << "check: wrote " << options->junit_path << "\n";
    if (missed > 0) line.exit_status = 1;
  });
}

}  // namespace msislab::app
