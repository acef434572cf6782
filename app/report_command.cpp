#include "app/report_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/method_catalogue.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "report/results_page.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {
/// Copies `from` to `to` whole; InputError naming the source on failure.
void copy_figure(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) io::fail_file(from.string(), "cannot copy to " + to.string() + ": " + ec.message());
}

/// What a page needs before anything is read: a .md path and something to report.
void check_report_options(const ReportOptions& options) {
  if (options.out_path.empty()) throw io::InputError("report: no output page given");
  if (fs::path(options.out_path).extension() != ".md") {
    io::fail_file(options.out_path,
                  "the page must end in .md (its figures go to the folder named "
                  "after it, without .md)");
  }
  if (options.sim_dir.empty() && options.real_dir.empty() && options.montecarlo_dirs.empty() &&
      options.sweep_dirs.empty() && options.sensitivity_csv.empty()) {
    throw io::InputError(
        "report: nothing to report (give --sim, --real, --montecarlo, --sweep or --sensitivity)");
  }
}

/// Reads every folder and file the page reports into results.
void read_report_inputs(const ReportOptions& options, report::ResultsReport& results) {
  if (!options.sim_dir.empty())
    results.sim = report::read_result_folder(results.styles, options.sim_dir, "sim");
  if (!options.real_dir.empty())
    results.real = report::read_result_folder(results.styles, options.real_dir, "real");
  for (const std::string& dir : options.montecarlo_dirs) {
    report::MonteCarloFolder mc = report::read_montecarlo_folder(dir);
    if (!results.montecarlo.empty()) {
      mc.label += "_" + fs::path(mc.manifest.scenario_source).stem().string();
      for (const report::MonteCarloFolder& earlier : results.montecarlo) {
        if (earlier.label == mc.label) {
          io::fail_file(dir, "a second Monte Carlo of " + mc.manifest.scenario_source +
                                 " (give each scenario once, the consistency test first)");
        }
      }
    }
    results.montecarlo.push_back(std::move(mc));
  }
  for (const std::string& dir : options.sweep_dirs) {
    results.sweeps.push_back(
        {dir, results::read_sweep_csv((fs::path(dir) / "sweep.csv").string())});
  }
  if (!options.sensitivity_csv.empty()) {
    results.sensitivity_source = options.sensitivity_csv;
    results.sensitivity = io::read_sensitivity_csv(options.sensitivity_csv);
  }
}
}  // namespace

ReportOutcome write_report(const ReportOptions& options) {
  const report::MethodStyles styles(
      MethodCatalogue::with_methods_file(options.methods_file).methods_file());
  check_report_options(options);
  report::ResultsReport results;
  results.styles = styles;
  const fs::path page = fs::absolute(options.out_path).lexically_normal();
  results.figures_dir_name = page.stem().string();
  const fs::path figures = fs::path(options.out_path).replace_extension();
  std::vector<std::string> inputs = options.montecarlo_dirs;
  inputs.insert(inputs.end(), options.sweep_dirs.begin(), options.sweep_dirs.end());
  inputs.insert(inputs.end(), {options.sim_dir, options.real_dir, options.sensitivity_csv});
  io::check_output_file({options.out_path, "page", "report", inputs, false},
                        io::page_written_by_msislab);
  const io::OutputRequest figures_out{figures.string(), "report figures", "report", inputs, false};
  io::check_output_folder(figures_out);
  read_report_inputs(options, results);
  const std::string markdown = report::results_markdown(results);

  // The figures are staged beside their folder, which they replace whole.
  io::StagedFolder staged(figures_out);
  const fs::path scratch(staged.path());
  ReportOutcome outcome;
  const auto copy_all = [&](const std::string& dir, const std::string& label,
                            const std::vector<std::string>& names) {
    for (const std::string& name : names) {
      copy_figure(fs::path(dir) / "figures" / name, scratch / (label + "_" + name));
      outcome.figures.push_back((figures / (label + "_" + name)).string());
    }
  };
  if (results.sim) copy_all(results.sim->dir, "sim", results.sim->figures);
  if (results.real) copy_all(results.real->dir, "real", results.real->figures);
  for (const report::MonteCarloFolder& mc : results.montecarlo)
    copy_all(mc.dir, mc.label, mc.figures);
  staged.commit();
  io::write_file_atomically(
      page.string(), [&](std::ostream& out) { out << io::page_signature("report") << markdown; });
  return outcome;
}

void add_report_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* report = app.add_subcommand(
      "report",
      "Write the results page (Table I on simulated and real data, the Monte Carlo consistency "
      "table, the figures) from folders that run, plot and montecarlo filled");
  report
      ->add_option("OUT_MD", options->out_path,
                   "The Markdown page; its figures are copied into <stem>/ beside it")
      ->required();
  report->add_option("--sim", options->sim_dir,
                     "Folder of result directories on a simulated dataset, plotted");
  report->add_option("--real", options->real_dir,
                     "Folder of result directories on the real dataset, plotted");
  report->add_option("--montecarlo", options->montecarlo_dirs,
                     "Monte Carlo directory, plotted; repeat for further scenarios, the page's "
                     "consistency test first");
  report->add_option("--sweep", options->sweep_dirs,
                     "Sweep directory (msislab sweep): its sweep.csv as a table; repeatable");
  report->add_option("--sensitivity", options->sensitivity_csv,
                     "The CSV of tools/real_sensitivity.sh: the real result's sensitivity to each "
                     "parameter, as a section");
  report->add_option("--methods-file", options->methods_file,
                     "Methods file (YAML): titles, colours and line styles of external methods "
                     "(without it they are listed under their names)");
  report->callback([options] {
    const ReportOutcome outcome = write_report(*options);
    std::cout << "wrote " << options->out_path << " and " << outcome.figures.size()
              << " figures beside it" << std::endl;
  });
}

}  // namespace msislab::app
