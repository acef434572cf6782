// The msislab command line: parses arguments and calls the app/ commands. Exit status 0 on success,
// 2 on bad input with one line on stderr naming the file, line or key (docs/cli.md).
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "app/eval_command.hpp"
#include "app/fidelity_command.hpp"
#include "app/image_command.hpp"
#include "app/methods.hpp"
#include "app/montecarlo_command.hpp"
#include "app/plot_command.hpp"
#include "app/report_command.hpp"
#include "app/run_command.hpp"
#include "app/scans_command.hpp"
#include "app/segment_command.hpp"
#include "app/simulate_command.hpp"
#include "app/sweep_command.hpp"
#include "io/input_error.hpp"
#include "plot/display.hpp"

namespace {

constexpr int kBadInput = 2;

std::string method_list() {
  std::string methods;
  for (const std::string& m : msislab::app::method_names()) {
    methods += (methods.empty() ? "" : ", ") + m;
  }
  return methods;
}

void add_run_command(CLI::App& app, msislab::app::RunOptions& options) {
  CLI::App* run = app.add_subcommand(
      "run",
      "Run a method on a dataset directory (real or synthetic) and write a result directory");
  run->add_option("DATASET_DIR", options.dataset_dir,
                  "Dataset directory (*_DVL.log, *_MTi.log, optional *_DGPS.log, calibration.yaml, "
                  "truth/)")
      ->required();
  run->add_option("--method,-m", options.method, "Method: " + method_list())->required();
  run->add_option("--out,-o", options.out_dir,
                  "Result directory (trajectory.tum, metrics.json when truth exists)")
      ->required();
  run->add_option("--config,-c", options.config_path,
                  "SLAM config YAML (defaults when absent; keys in docs/formats.md)");
}

void add_eval_command(CLI::App& app, msislab::app::EvalOptions& options) {
  CLI::App* eval = app.add_subcommand(
      "eval",
      "Re-score a result directory of `msislab run` against truth; rewrites metrics.json and "
      "nees.csv");
  eval->add_option("RESULT_DIR", options.result_dir,
                   "Result directory (trajectory.tum, metrics.json, scans.csv)")
      ->required();
  eval->add_option("--truth,-t", options.truth_path,
                   "TUM truth file (default: the truth of the dataset recorded in metrics.json)");
  eval->add_option("--config,-c", options.config_path,
                   "SLAM config YAML whose segments replace the recorded segment windows");
}

void add_report_command(CLI::App& app, msislab::app::ReportOptions& options) {
  CLI::App* report = app.add_subcommand(
      "report",
      "Write the results page (Table I on simulated and real data, the Monte Carlo consistency "
      "table, the figures) from folders that run, plot and montecarlo filled");
  report
      ->add_option("OUT_MD", options.out_path,
                   "The Markdown page; its figures are copied into <stem>/ beside it")
      ->required();
  report->add_option("--sim", options.sim_dir,
                     "Folder of result directories on a simulated dataset, plotted");
  report->add_option("--real", options.real_dir,
                     "Folder of result directories on the real dataset, plotted");
  report->add_option("--montecarlo", options.montecarlo_dirs,
                     "Monte Carlo directory, plotted; repeat for further scenarios, the page's "
                     "consistency test first");
  report->add_option("--sweep", options.sweep_dirs,
                     "Sweep directory (msislab sweep): its sweep.csv as a table; repeatable");
}

void add_montecarlo_command(CLI::App& app, msislab::app::MonteCarloOptions& options,
                            msislab::app::MergeOptions& merge, bool& no_plot) {
  CLI::App* mc = app.add_subcommand(
      "montecarlo",
      "N seeded repetitions of simulate + every method, each run in a worker process that keeps "
      "the dataset in memory; resumable and shardable, one command per directory; writes per-run "
      "results, summary.json, nees.csv and figures");
  mc->add_option("SCENARIO", options.scenario_path, "Scenario YAML (required unless merge)");
  mc->add_option("--runs,-n", options.runs, "Number of runs N (required); run r uses seed + r");
  mc->add_option("--out,-o", options.out_dir,
                 "Monte Carlo directory (required); an existing one is resumed");
  mc->add_option("--methods,-m", options.methods,
                 "Comma-separated methods (default: robocentric,worldcentric; available: " +
                     method_list() + ")")
      ->delimiter(',');
  mc->add_option("--jobs,-j", options.jobs,
                 "Runs at once (default: one per hardware thread; above 1 each simulation uses "
                 "one thread)");
  mc->add_option("--config,-c", options.config_path, "SLAM config YAML for every run");
  mc->add_option("--shard", options.shard,
                 "i/N: only the runs r with r % N == i (0 <= i < N); merge the shards afterwards");
  mc->add_flag("--keep-datasets", options.keep_datasets,
               "Also write each run's simulated dataset to DIR/datasets/run_<rrrr> (about 70 MB "
               "each on the St. Pere replica)");
  mc->add_flag("--no-plot", no_plot,
               "Do not draw the figures at the end (shards never draw; see msislab plot)");
  mc->require_subcommand(0, 1);
  CLI::App* m = mc->add_subcommand(
      "merge", "Merge shard directories into OUT_DIR and write its summary over every run");
  m->add_option("OUT_DIR", merge.out_dir, "Monte Carlo directory to write")->required();
  m->add_option("SHARD_DIR", merge.shard_dirs, "Shard directories made with --shard")->required();
  m->add_flag("--no-plot", no_plot, "Do not draw the figures at the end");
}

/// The figures of a Monte Carlo or sweep directory, drawn by `msislab plot DIR` in a child process
/// and listed as "COMMAND: wrote FILE"; a failure to draw is reported on stderr and leaves the
/// statistics (and the exit status) alone.
void draw_figures(const std::string& command, const std::string& dir) {
  const std::string failure = msislab::app::draw_montecarlo_figures(dir);
  if (!failure.empty()) {
    std::cerr << command << ": figures not drawn (" << failure << "); draw them with `msislab plot "
              << dir << "`" << std::endl;
    return;
  }
  std::vector<std::string> figures;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/figures")) {
    if (entry.path().extension() == ".png") figures.push_back(entry.path().filename().string());
  }
  std::sort(figures.begin(), figures.end());
  for (const std::string& name : figures) {
    std::cout << command << ": wrote " << dir << "/figures/" << name << "\n";
  }
  std::cout.flush();
}

struct SweepCli {
  msislab::app::SweepOptions options;
  std::string merge_out;
  std::vector<std::string> merge_shards;
  bool no_plot = false;
  CLI::App* command = nullptr;
};

void add_sweep_command(CLI::App& app, SweepCli& cli) {
  cli.command = app.add_subcommand(
      "sweep",
      "A Monte Carlo directory per cell of a grid (or list) of scenario and SLAM config overrides; "
      "resumable and shardable; writes sweep.csv and figures");
  cli.command->add_option("SWEEP", cli.options.sweep_path, "Sweep YAML (required unless merge)");
  cli.command->add_option("--out,-o", cli.options.out_dir,
                          "Sweep directory (required); an existing one is resumed");
  cli.command->add_option("--jobs,-j", cli.options.jobs,
                          "Runs at once in each cell (default: one per hardware thread)");
  cli.command->add_option("--shard", cli.options.shard,
                          "i/N: in every cell only the runs r with r % N == i; merge afterwards");
  cli.command->add_flag("--no-plot", cli.no_plot, "Do not draw the figures at the end");
  cli.command->require_subcommand(0, 1);
  CLI::App* m = cli.command->add_subcommand(
      "merge", "Merge sweep shard directories into OUT_DIR, cell by cell, and write sweep.csv");
  m->add_option("OUT_DIR", cli.merge_out, "Sweep directory to write")->required();
  m->add_option("SHARD_DIR", cli.merge_shards, "Shard directories made with --shard")->required();
  m->add_flag("--no-plot", cli.no_plot, "Do not draw the figures at the end");
}

/// Runs `sweep` or `sweep merge`; the exit status.
int run_sweep_command(SweepCli& cli) {
  msislab::app::SweepOutcome outcome;
  std::string dir;
  if (cli.command->got_subcommand("merge")) {
    dir = cli.merge_out;
    outcome = msislab::app::merge_sweep(cli.merge_out, cli.merge_shards);
  } else {
    if (cli.options.sweep_path.empty()) throw msislab::io::InputError("sweep: SWEEP is required");
    if (cli.options.out_dir.empty()) throw msislab::io::InputError("sweep: --out is required");
    dir = cli.options.out_dir;
    outcome = msislab::app::sweep(cli.options, {std::cerr, isatty(STDERR_FILENO) == 1});
    if (outcome.interrupted != 0) {
      std::cerr << "sweep: stopped by " << sigabbrev_np(outcome.interrupted)
                << "; every worker ended, the finished runs are kept in " << dir
                << "; run the same command to resume" << std::endl;
      return 128 + outcome.interrupted;
    }
  }
  std::cout << "sweep: " << dir << " holds " << outcome.cells << " cells (" << outcome.executed
            << " runs done now, " << outcome.failed << " with a failed method); wrote sweep.csv"
            << std::endl;
  if (!cli.no_plot && cli.options.shard.empty()) draw_figures("sweep", dir);
  return 0;
}

void check_montecarlo_options(const msislab::app::MonteCarloOptions& options,
                              const CLI::App& montecarlo) {
  const auto missing = [](const std::string& what) {
    throw msislab::io::InputError("montecarlo: " + what + " is required");
  };
  if (options.scenario_path.empty()) missing("SCENARIO");
  if (montecarlo.count("--runs") == 0) missing("--runs");
  if (options.out_dir.empty()) missing("--out");
}

void print_montecarlo(const msislab::app::MonteCarloOutcome& outcome, const std::string& dir,
                      bool merged) {
  std::cout << "montecarlo: " << dir << " holds " << outcome.runs << " runs";
  if (merged) {
    std::cout << " (merged)";
  } else {
    std::cout << " (" << outcome.executed << " run now, " << outcome.runs - outcome.executed
              << " already done)";
  }
  std::cout << ", " << outcome.failed << " with a failed method; wrote summary.json and nees.csv\n"
            << std::fixed << std::setprecision(3);
  for (const msislab::MethodSummary& s : outcome.summary) {
    std::cout << "  " << s.method << ": " << s.runs << " finished, " << s.failed << " failed";
    if (s.mean_error_m) std::cout << ", mean error " << *s.mean_error_m << " m";
    if (s.anees) std::cout << ", ANEES " << *s.anees;
    if (s.nees_in_bounds_fraction) {
      std::cout << std::setprecision(1) << ", NEES in bounds " << 100.0 * *s.nees_in_bounds_fraction
                << " %" << std::setprecision(3);
    }
    std::cout << "\n";
  }
  std::cout << std::flush;
}

void add_simulate_command(CLI::App& app, msislab::app::SimulateOptions& options) {
  CLI::App* simulate = app.add_subcommand(
      "simulate", "Render a synthetic dataset (St. Pere log formats plus truth/) from a scenario");
  simulate->add_option("SCENARIO", options.scenario_path, "Scenario YAML (docs/simulator.md)")
      ->required();
  simulate->add_option("--out,-o", options.out_dir, "Dataset directory to write")->required();
  simulate->add_option("--seed", options.seed, "Seed overriding the scenario's");
  simulate
      ->add_option("--threads,-j", options.threads,
                   "Worker threads (default: one per hardware thread; the output is the same "
                   "for any count)")
      ->check(CLI::NonNegativeNumber);
}

void add_image_command(CLI::App& app, msislab::app::ImageOptions& options) {
  CLI::App* image = app.add_subcommand(
      "image", "Draw one sonar revolution of a dataset's *_IS.log as an acoustic image (PNG)");
  image->add_option("DATASET_DIR", options.dataset_dir, "Dataset directory with a *_IS.log")
      ->required();
  image->add_option("--out,-o", options.out_path, "PNG file to write")->required();
  image->add_option("--revolution,-r", options.revolution, "0-based revolution to draw")
      ->check(CLI::NonNegativeNumber);
  image->add_option("--size", options.size_px, "Image width and height in pixels")
      ->check(CLI::Range(100, 4000));
}

void add_segment_command(CLI::App& app, msislab::app::SegmentOptions& options) {
  CLI::App* segment = app.add_subcommand(
      "segment",
      "Score beam segmentation methods on a simulated dataset against its truth/beams.csv");
  segment
      ->add_option("DATASET_DIR", options.dataset_dir,
                   "Simulated dataset directory (*_IS.log, truth/beams.csv)")
      ->required();
  segment->add_option("--method,-m", options.methods,
                      "Methods: max_intensity, threshold_groups, smoothed_first or all (default)");
  segment
      ->add_option("--threshold", options.threshold,
                   "Intensity threshold 0..255 (default: the SegmentationConfig default)")
      ->check(CLI::Range(0.0, 255.0));
  segment
      ->add_option("--min-range", options.min_range_m,
                   "Minimum range in m (default: the SegmentationConfig default)")
      ->check(CLI::NonNegativeNumber);
  segment->add_option("--out,-o", options.out_path, "Also write the Markdown table to this file");
}

void add_scans_command(CLI::App& app, msislab::app::ScansOptions& options) {
  CLI::App* scans = app.add_subcommand(
      "scans",
      "Segment the sonar beams and build motion-compensated scans placed by dead "
      "reckoning; writes scans.csv, map.ply, map.png and compensation.png");
  scans->add_option("DATASET_DIR", options.dataset_dir, "Dataset directory, real or synthetic")
      ->required();
  scans->add_option("--out,-o", options.out_dir, "Output directory")->required();
  scans->add_option("--config,-c", options.config_path,
                    "SLAM config YAML (segmentation and dead_reckoning sections)");
  scans->add_option("--figure-scan", options.figure_scan,
                    "Scan drawn before/after compensation (default: the middle one)");
}

void add_plot_command(CLI::App& app, msislab::app::PlotOptions& options) {
  CLI::App* plot = app.add_subcommand(
      "plot",
      "Draw the figures of a result, comparison or Monte Carlo directory as PNG into DIR/figures/ "
      "(VTK: needs an X display, else reruns itself under xvfb-run)");
  plot->add_option("DIR", options.dir,
                   "A result directory (trajectory.tum), a folder of result directories, or a "
                   "Monte Carlo directory (nees.csv)")
      ->required();
  plot->add_option("--dataset,-d", options.dataset_dir,
                   "Dataset directory for the truth and the acoustic image (default: the one "
                   "recorded in metrics.json)");
  plot->add_option("--ellipse-every", options.ellipse_every,
                   "Draw the 2-sigma ellipse of every k-th scan (default: about 25 per figure)")
      ->check(CLI::PositiveNumber);
  plot->add_option("--width", options.width_px, "Figure width in pixels")
      ->check(CLI::Range(400, 4000));
  plot->add_option("--height", options.height_px, "Figure height in pixels")
      ->check(CLI::Range(300, 4000));
  plot->add_option("--revolution,-r", options.revolution,
                   "Sonar revolution of the acoustic image (default: the middle one)")
      ->check(CLI::NonNegativeNumber);
}

/// Reads every input first (bad input fails without a display), then draws; VTK needs an X
/// display, so without one the command runs again under xvfb-run.
void run_plot(const msislab::app::PlotOptions& options, int argc, char** argv) {
  const msislab::app::PlotInputs inputs = msislab::app::load_plot_inputs(options);
  if (!msislab::plot::x_display_available()) msislab::plot::rerun_under_xvfb(argc, argv);
  for (const std::string& file : msislab::app::draw_plot(inputs)) {
    std::cout << "wrote " << file << "\n";
  }
  std::cout << std::flush;
}

void add_fidelity_command(CLI::App& app, msislab::app::FidelityOptions& options) {
  CLI::App* fidelity = app.add_subcommand(
      "fidelity",
      "Compare a simulated dataset with the real one, statistic by statistic, from their "
      "detections: prints a Markdown table (values, sim / real, KS distance); --out also writes "
      "fidelity.md, fidelity.json and figures (VTK: needs an X display, else reruns itself under "
      "xvfb-run)");
  fidelity
      ->add_option("REAL_DATASET", options.real_dir,
                   "Real dataset directory (*_detections.csv[.gz], *_IS_timestamps.log)")
      ->required();
  fidelity
      ->add_option("SIM_DATASET", options.sim_dir,
                   "Simulated dataset directory, in the same formats and sonar setup")
      ->required();
  fidelity->add_option("--out,-o", options.out_dir,
                       "Report folder (fidelity.md, fidelity.json, figures/), replaced whole");
  fidelity->add_option("--revolution-real", options.revolution_real,
                       "Keyframe of the real detections drawn in revolution.png (default: the "
                       "middle one)");
  fidelity->add_option("--revolution-sim", options.revolution_sim,
                       "Keyframe of the simulated detections drawn (default: the one nearest in "
                       "time to the real one drawn when the runs overlap in time, else the middle "
                       "one)");
}

/// Reads both datasets and computes the table first (bad input fails without a display); the
/// figures of --out need one, so without it the command runs again under xvfb-run.
void run_fidelity(const msislab::app::FidelityOptions& options, int argc, char** argv) {
  const msislab::app::FidelityReport report = msislab::app::compare_datasets(options);
  if (!options.out_dir.empty() && !msislab::plot::x_display_available()) {
    msislab::plot::rerun_under_xvfb(argc, argv);
  }
  std::cout << msislab::app::fidelity_markdown(report.table);
  if (!options.out_dir.empty()) {
    std::cout << "\n";
    for (const std::string& file : msislab::app::write_fidelity(report)) {
      std::cout << "wrote " << file << "\n";
    }
  }
  std::cout << std::flush;
}

/// Every subcommand's options, filled by CLI11 when the command line is parsed.
struct Options {
  msislab::app::RunOptions run;
  msislab::app::EvalOptions eval;
  msislab::app::SimulateOptions simulate;
  msislab::app::MonteCarloOptions montecarlo;
  msislab::app::MergeOptions merge;
  bool montecarlo_no_plot = false;
  SweepCli sweep;
  msislab::app::ImageOptions image;
  msislab::app::ScansOptions scans;
  msislab::app::SegmentOptions segment;
  msislab::app::PlotOptions plot;
  msislab::app::ReportOptions report;
  msislab::app::FidelityOptions fidelity;
};

void add_commands(CLI::App& app, Options& o) {
  add_run_command(app, o.run);
  add_eval_command(app, o.eval);
  add_simulate_command(app, o.simulate);
  add_montecarlo_command(app, o.montecarlo, o.merge, o.montecarlo_no_plot);
  add_sweep_command(app, o.sweep);
  add_image_command(app, o.image);
  add_scans_command(app, o.scans);
  add_segment_command(app, o.segment);
  add_plot_command(app, o.plot);
  add_report_command(app, o.report);
  add_fidelity_command(app, o.fidelity);
}

void run_simulate(const msislab::app::SimulateOptions& options) {
  const msislab::app::SimulateSummary s = msislab::app::simulate(options);
  std::cout << std::fixed << std::setprecision(2) << "wrote " << options.out_dir << ": " << s.beams
            << " beams (" << s.rays_per_beam << " rays each), " << s.dvl_samples
            << " DVL samples over " << s.duration_s << " s; simulated in " << s.render_s << " s ("
            << s.duration_s / std::max(s.render_s, 1e-9) << "x real time), " << s.total_s
            << " s in all" << std::endl;
}

void run_scans(const msislab::app::ScansOptions& options) {
  const msislab::app::ScansSummary s = msislab::app::build_scans_command(options);
  std::cout << "wrote " << options.out_dir << ": " << s.scans << " scans, " << s.points
            << " points from " << s.beams_with_readings << " of " << s.beams << " beams ("
            << s.source << ")";
  if (s.compensated_error_m) {
    std::cout << std::fixed << std::setprecision(3)
              << "; reading placement error against the truth: " << *s.compensated_error_m
              << " m compensated, " << *s.uncompensated_error_m << " m uncompensated";
  }
  std::cout << std::endl;
}

void run_run(const msislab::app::RunOptions& options) {
  const msislab::app::RunOutcome outcome = msislab::app::run(options);
  std::cout << "wrote " << options.out_dir << "/trajectory.tum (" << outcome.trajectory.size()
            << " poses)";
  if (outcome.metrics) {
    std::cout << std::fixed << std::setprecision(3) << "; mean error "
              << outcome.metrics->errors.mean_m << " m against " << outcome.metrics->truth
              << ", metrics.json";
  }
  std::cout << std::endl;
}

void run_eval(const msislab::app::EvalOptions& options) {
  const msislab::app::EvalOutcome outcome = msislab::app::evaluate(options);
  std::cout << std::fixed << std::setprecision(3) << "wrote " << options.result_dir
            << "/metrics.json: mean error " << outcome.metrics.errors.mean_m << " m against "
            << outcome.metrics.truth;
  if (outcome.metrics.anees) {
    std::cout << ", ANEES " << *outcome.metrics.anees << " over " << outcome.nees_rows
              << " scans (nees.csv)";
  }
  std::cout << std::endl;
}

/// `montecarlo` or `montecarlo merge`; the exit status (128 + the signal when stopped).
int run_montecarlo(CLI::App& montecarlo, const Options& o) {
  if (montecarlo.got_subcommand("merge")) {
    print_montecarlo(msislab::app::merge_montecarlo(o.merge), o.merge.out_dir, true);
    if (!o.montecarlo_no_plot) draw_figures("montecarlo", o.merge.out_dir);
    return 0;
  }
  check_montecarlo_options(o.montecarlo, montecarlo);
  const msislab::app::MonteCarloOutcome outcome =
      msislab::app::montecarlo(o.montecarlo, {std::cerr, isatty(STDERR_FILENO) == 1});
  if (outcome.interrupted != 0) {
    std::cerr << "montecarlo: stopped by " << sigabbrev_np(outcome.interrupted)
              << "; every worker ended, the finished runs are kept in " << o.montecarlo.out_dir
              << "; run the same command to resume" << std::endl;
    return 128 + outcome.interrupted;
  }
  print_montecarlo(outcome, o.montecarlo.out_dir, false);
  if (!o.montecarlo_no_plot && o.montecarlo.shard.empty()) {
    draw_figures("montecarlo", o.montecarlo.out_dir);
  }
  return 0;
}

/// Runs the one subcommand given; its exit status.
int run_command(CLI::App& app, Options& o, int argc, char** argv) {
  if (app.got_subcommand("simulate")) run_simulate(o.simulate);
  if (app.got_subcommand("scans")) run_scans(o.scans);
  if (app.got_subcommand("image")) {
    msislab::app::draw_image(o.image);
    std::cout << "wrote " << o.image.out_path << std::endl;
  }
  if (app.got_subcommand("plot")) run_plot(o.plot, argc, argv);
  if (app.got_subcommand("fidelity")) run_fidelity(o.fidelity, argc, argv);
  if (app.got_subcommand("segment"))
    std::cout << msislab::app::segment(o.segment).markdown << std::flush;
  if (app.got_subcommand("run")) run_run(o.run);
  if (app.got_subcommand("report")) {
    const msislab::app::ReportOutcome outcome = msislab::app::write_report(o.report);
    std::cout << "wrote " << o.report.out_path << " and " << outcome.figures.size()
              << " figures beside it" << std::endl;
  }
  if (app.got_subcommand("eval")) run_eval(o.eval);
  if (app.got_subcommand("sweep")) return run_sweep_command(o.sweep);
  if (app.got_subcommand("montecarlo")) return run_montecarlo(*app.get_subcommand("montecarlo"), o);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"msislab: a testbed for underwater SLAM with a mechanically scanned imaging sonar"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "msislab " MSISLAB_VERSION);  // project(VERSION) in CMake
  Options options;
  add_commands(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "msislab: " << e.what() << " (see msislab --help)\n";
    return kBadInput;
  }
  try {
    return run_command(app, options, argc, argv);
  } catch (const msislab::io::InputError& e) {
    std::cerr << "msislab: " << e.what() << "\n";
    return kBadInput;
  }
}
