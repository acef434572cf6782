#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/montecarlo.hpp"
#include "io/input_error.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// `montecarlo` or `montecarlo merge`'s options.
struct MonteCarloCli {
  MonteCarloOptions options;
  MergeOptions merge;
  bool no_plot = false;
  CLI::App* command = nullptr;
};

void check_montecarlo_options(const MonteCarloCli& cli) {
  const auto missing = [](const std::string& what) {
    throw io::InputError("montecarlo: " + what + " is required");
  };
  if (cli.options.scenario_path.empty()) missing("SCENARIO");
  if (cli.command->count("--runs") == 0) missing("--runs");
  if (cli.options.out_dir.empty()) missing("--out");
}

void print_montecarlo(const MonteCarloOutcome& outcome, const std::string& dir, bool merged) {
  std::cout << "montecarlo: " << dir << " holds " << outcome.runs << " runs";
  if (merged) {
    std::cout << " (merged)";
  } else {
    std::cout << " (" << outcome.executed << " run now, " << outcome.runs - outcome.executed
              << " already done)";
  }
  std::cout << ", " << outcome.failed << " with a failed method; wrote summary.json and nees.csv\n"
            << std::fixed << std::setprecision(3);
  for (const MethodSummary& s : outcome.summary) {
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

/// Where a Monte Carlo directory's failed.json files are, as a shell pattern.
std::string failed_json(const std::string& dir) {
  return (fs::path(dir) / "runs" / "*" / "run_*" / "failed.json").string();
}

/// `montecarlo` or `montecarlo merge`; the exit status (kRunsFailedStatus when a run has a failed
/// method, 128 + the signal when stopped).
int run_montecarlo_cli(const MonteCarloCli& cli) {
  if (cli.command->got_subcommand("merge")) {
    // Runs no shard has yet (an unfinished shard) are `missing`, not failed: the status stays 0.
    const MonteCarloOutcome merged = merge_montecarlo(cli.merge);
    print_montecarlo(merged, cli.merge.out_dir, true);
    if (!cli.no_plot) draw_and_list_figures("montecarlo", cli.merge.out_dir);
    return failed_runs_status("montecarlo merge", merged.failed, merged.runs,
                              failed_json(cli.merge.out_dir));
  }
  check_montecarlo_options(cli);
  const MonteCarloOutcome outcome =
      montecarlo(cli.options, {std::cerr, isatty(STDERR_FILENO) == 1});
  if (outcome.interrupted != 0) {
    std::cerr << "montecarlo: stopped by " << sigabbrev_np(outcome.interrupted)
              << "; every worker ended, the finished runs are kept in " << cli.options.out_dir
              << "; run the same command to resume" << std::endl;
    return 128 + outcome.interrupted;
  }
  print_montecarlo(outcome, cli.options.out_dir, false);
  if (!cli.no_plot && cli.options.shard.empty()) {
    draw_and_list_figures("montecarlo", cli.options.out_dir);
  }
  return failed_runs_status("montecarlo", outcome.failed, outcome.runs,
                            failed_json(cli.options.out_dir));
}

}  // namespace

void add_montecarlo_command(CLI::App& app, CommandLine& line) {
  auto cli = std::make_shared<MonteCarloCli>();
  MonteCarloOptions& options = cli->options;
  CLI::App* mc = cli->command = app.add_subcommand(
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
                 "one thread)")
      ->check(CLI::PositiveNumber);
  mc->add_option("--config,-c", options.config_path, "SLAM config YAML for every run");
  mc->add_option("--shard", options.shard,
                 "i/N: only the runs r with r % N == i (0 <= i < N); merge the shards afterwards");
  mc->add_option("--methods-file", options.methods_file,
                 "Methods file (YAML) declaring external methods for --methods; copied to "
                 "DIR/methods.yaml (docs/formats.md)");
  mc->add_flag("--keep-datasets", options.keep_datasets,
               "Also write each run's simulated dataset to DIR/datasets/run_<rrrr> (about 70 MB "
               "each on the St. Pere replica); without it an external method's dataset is "
               "written to DIR/scratch and removed after its run");
  mc->add_flag("--no-plot", cli->no_plot,
               "Do not draw the figures at the end (shards never draw; see msislab plot)");
  mc->require_subcommand(0, 1);
  CLI::App* m = mc->add_subcommand(
      "merge", "Merge shard directories into OUT_DIR and write its summary over every run");
  m->add_option("OUT_DIR", cli->merge.out_dir, "Monte Carlo directory to write")->required();
  m->add_option("SHARD_DIR", cli->merge.shard_dirs, "Shard directories made with --shard")
      ->required();
  m->add_flag("--no-plot", cli->no_plot, "Do not draw the figures at the end");
  mc->callback([cli, &line] { line.exit_status = run_montecarlo_cli(*cli); });
}

}  // namespace msislab::app
