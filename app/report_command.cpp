#include "app/report_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/methods.hpp"
#include "app/plot_figures.hpp"
#include "app/plot_inputs.hpp"
#include "io/atomic_file.hpp"
#include "io/dataset.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {
/// PNG files of DIR/figures, sorted; InputError when the folder is missing or holds none.
std::vector<std::string> figures_of(const std::string& dir) {
  const fs::path folder = fs::path(dir) / "figures";
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".png") {
      names.push_back(entry.path().filename().string());
    }
  }
  if (names.empty()) {
    io::fail_file(folder.string(), "no figures (draw them first: msislab plot " + dir + ")");
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Copies `from` to `to` whole; InputError naming the source on failure.
void copy_figure(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) io::fail_file(from.string(), "cannot copy to " + to.string() + ": " + ec.message());
}

/// A dataset's name: the prefix of its *_DVL.log ("stpere_replica", "_040825_1735"), else the name
/// of its folder; empty when no dataset is recorded.
std::string dataset_name(const std::string& dataset_dir) {
  if (dataset_dir.empty()) return "";
  if (fs::is_directory(dataset_dir)) {
    const io::DatasetFiles files = io::find_dataset_files(dataset_dir);
    if (files.dvl) {
      const std::string log = fs::path(*files.dvl).filename().string();
      return log.substr(0, log.size() - std::string("_DVL.log").size());
    }
  }
  return fs::path(dataset_dir).lexically_normal().filename().string();
}

}  // namespace

ResultFolder read_result_folder(const std::string& dir, const std::string& label) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  ResultFolder folder;
  folder.label = label;
  folder.dir = dir;
  for (const fs::path& sub : result_subdirs(dir)) {
    if (!fs::is_regular_file(sub / "metrics.json")) continue;  // run without truth: no scores
    const io::StoredMetrics stored = io::read_metrics_json((sub / "metrics.json").string());
    if (folder.dataset.empty()) folder.dataset = stored.dataset_dir;
    folder.results.push_back(stored.metrics);
  }
  if (folder.results.empty()) {
    io::fail_file(dir, "no result directories (subdirectories with a metrics.json)");
  }
  std::stable_sort(folder.results.begin(), folder.results.end(),
                   [](const RunMetrics& a, const RunMetrics& b) {
                     return method_rank(a.method) < method_rank(b.method);
                   });
  folder.figures = figures_of(dir);
  folder.scenario = dataset_name(folder.dataset);
  return folder;
}

MonteCarloFolder read_montecarlo_folder(const std::string& dir) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  MonteCarloFolder mc;
  mc.label = "montecarlo";
  mc.dir = dir;
  mc.manifest = io::read_manifest_json((fs::path(dir) / "montecarlo.json").string());
  const fs::path summary = fs::path(dir) / "summary.json";
  if (!fs::is_regular_file(summary)) {
    io::fail_file(summary.string(), "missing (the Monte Carlo has not finished or been merged)");
  }
  mc.methods = io::read_summary_json(summary.string());
  mc.figures = figures_of(dir);
  return mc;
}

ReportOutcome write_report(const ReportOptions& options) {
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
  ResultsReport report;
  const fs::path page = fs::absolute(options.out_path).lexically_normal();
  report.figures_dir_name = page.stem().string();
  const fs::path figures = fs::path(options.out_path).replace_extension();
  std::vector<std::string> inputs = options.montecarlo_dirs;
  inputs.insert(inputs.end(), options.sweep_dirs.begin(), options.sweep_dirs.end());
  inputs.insert(inputs.end(), {options.sim_dir, options.real_dir, options.sensitivity_csv});
  io::check_output_file({options.out_path, "page", "report", inputs, false},
                        io::page_written_by_msislab);
  const io::OutputRequest figures_out{figures.string(), "report figures", "report", inputs, false};
  io::check_output_folder(figures_out);
  if (!options.sim_dir.empty()) report.sim = read_result_folder(options.sim_dir, "sim");
  if (!options.real_dir.empty()) report.real = read_result_folder(options.real_dir, "real");
  for (const std::string& dir : options.montecarlo_dirs) {
    MonteCarloFolder mc = read_montecarlo_folder(dir);
    if (!report.montecarlo.empty()) {
      mc.label += "_" + fs::path(mc.manifest.scenario_source).stem().string();
      for (const MonteCarloFolder& earlier : report.montecarlo) {
        if (earlier.label == mc.label) {
          io::fail_file(dir, "a second Monte Carlo of " + mc.manifest.scenario_source +
                                 " (give each scenario once, the consistency test first)");
        }
      }
    }
    report.montecarlo.push_back(std::move(mc));
  }
  for (const std::string& dir : options.sweep_dirs) {
    report.sweeps.push_back({dir, io::read_sweep_csv((fs::path(dir) / "sweep.csv").string())});
  }
  if (!options.sensitivity_csv.empty()) {
    report.sensitivity_source = options.sensitivity_csv;
    report.sensitivity = io::read_sensitivity_csv(options.sensitivity_csv);
  }
  const std::string markdown = results_markdown(report);

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
  if (report.sim) copy_all(report.sim->dir, "sim", report.sim->figures);
  if (report.real) copy_all(report.real->dir, "real", report.real->figures);
  for (const MonteCarloFolder& mc : report.montecarlo) copy_all(mc.dir, mc.label, mc.figures);
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
  report->callback([options] {
    const ReportOutcome outcome = write_report(*options);
    std::cout << "wrote " << options->out_path << " and " << outcome.figures.size()
              << " figures beside it" << std::endl;
  });
}

}  // namespace msislab::app
