#include "app/montecarlo_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "app/cli.hpp"
#include "app/directory_lock.hpp"
#include "app/montecarlo_directory.hpp"
#include "app/montecarlo_runs.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "app/run_method.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/input_error.hpp"
#include "io/montecarlo_files.hpp"
#include "io/scenario_scene.hpp"
#include "io/text_lines.hpp"
#include "report/methods.hpp"
#include "sim/navigation_sensors.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

void check_methods(const std::vector<std::string>& methods) {
  if (methods.empty()) throw io::InputError("--methods: no method given");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    report::method_info(methods[i], "--methods");
    if (std::find(methods.begin(), methods.begin() + static_cast<long>(i), methods[i]) !=
        methods.begin() + static_cast<long>(i)) {
      throw io::InputError("--methods '" + methods[i] + "': given twice");
    }
  }
}

/// Reads and checks every input and locks the directory; then makes or resumes it: scenario.yaml
/// and config.yaml copies, montecarlo.json.
RunContext prepare(const MonteCarloOptions& options, std::optional<DirectoryLock>& lock) {
  report::load_methods_file(options.methods_file);
  check_methods(options.methods);
  RunContext ctx;
  io::MonteCarloManifest& manifest = ctx.manifest;
  check_shard_and_jobs(options.shard, options.jobs, manifest.shard_index, manifest.shard_count);
  if (options.runs < 1) {
    throw io::InputError("--runs " + std::to_string(options.runs) + ": must be at least 1");
  }
  io::CheckedScenario checked = io::read_checked_scenario(options.scenario_path);
  for (const std::string& warning : checked.warnings) std::cerr << "msislab: " << warning << '\n';
  ctx.scenario = std::move(checked.scenario);
  ctx.mesh = std::move(checked.mesh);
  // Every run's dataset carries the scenario's navigation noise; the config is made over it once.
  io::DatasetConfig config = io::slam_config_for_dataset(
      options.config_path, io::navigation_noise_as_stored(sim::navigation_noise_of(ctx.scenario)),
      "the scenario");
  ctx.config = std::move(config.config);
  ctx.scenario_text = io::read_whole_file(options.scenario_path);
  DirectoryInputs inputs;
  inputs.scenario_text = ctx.scenario_text;
  if (!options.config_path.empty()) inputs.config_text = io::read_whole_file(options.config_path);
  if (!options.methods_file.empty())
    inputs.methods_text = io::read_whole_file(options.methods_file);
  manifest.executable_digest = executable_digest(self_executable());
  manifest.has_config = !options.config_path.empty();
  manifest.has_methods_file = !options.methods_file.empty();

  lock.emplace(io::OutputRequest{options.out_dir,
                                 "montecarlo",
                                 "montecarlo",
                                 {options.scenario_path, options.config_path,
                                  ctx.scenario.scene.mesh_path, options.methods_file},
                                 false},
               "msislab montecarlo " + options.scenario_path);
  check_resumable(options.out_dir, manifest, inputs, options.scenario_path);
  manifest.scenario_source = io::absolute_path(options.scenario_path);
  manifest.first_seed = ctx.scenario.seed;
  manifest.runs = options.runs;
  manifest.methods = options.methods;
  write_directory_header(options.out_dir, manifest, inputs);
  // Said once every input is checked (a bad input's message stays one line).
  if (!config.noise_note.empty()) std::cerr << "msislab: " << config.noise_note << '\n';
  ctx.dir = options.out_dir;
  ctx.keep_datasets = options.keep_datasets;
  return ctx;
}

}  // namespace

void check_shard_and_jobs(const std::string& shard, int jobs, int& shard_index, int& shard_count) {
  shard_index = 0;
  shard_count = 1;
  if (!shard.empty() && !io::parse_shard(shard, shard_index, shard_count)) {
    throw io::InputError("--shard '" + shard + "': expected i/N with 0 <= i < N");
  }
  if (jobs < 0) {
    throw io::InputError("--jobs " + std::to_string(jobs) +
                         ": must be 1 or more (leave it out for one per hardware thread)");
  }
}

MonteCarloOutcome montecarlo(const MonteCarloOptions& options, const MonteCarloLog& log) {
  std::optional<DirectoryLock> lock;
  RunContext ctx = prepare(options, lock);
  const std::string& dir = ctx.dir;
  const std::vector<int> runs = runs_of(ctx.manifest);
  remove_leftovers(dir, ctx.manifest.methods);  // of a command killed outright
  const std::vector<PendingRun> todo = pending_runs(ctx, runs);
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Several runs at once: one simulation thread each, so that J runs keep J cores busy.
  ctx.simulation_threads =
      std::min(static_cast<std::size_t>(jobs), todo.size()) > 1
          ? 1
          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  make_run_folders(ctx);
  // The scenario's rays do not depend on the seed: traced once for all runs, before any worker,
  // on as many threads as the runs would use between them.
  if (!todo.empty()) ctx.trace = trace_once(ctx, std::max(jobs, ctx.simulation_threads));

  MonteCarloOutcome outcome;
  outcome.runs = runs.size();
  Progress progress(runs.size(), runs.size() - todo.size(), log.terminal, log.log);
  progress.redraw();
  outcome.interrupted = execute_runs(ctx, todo, jobs, lock->fd(), progress, outcome.executed);
  progress.end();
  std::error_code ec;
  fs::remove(fs::path(dir) / "scratch", ec);  // only when empty
  if (outcome.interrupted != 0) {
    outcome.failed = failed_runs(dir, ctx.manifest.methods, runs);
    return outcome;
  }
  outcome.summary = write_summary_files(dir, ctx.manifest, runs);
  outcome.failed = failed_runs(dir, ctx.manifest.methods, runs);
  return outcome;
}

std::string draw_montecarlo_figures(const std::string& dir, const std::string& executable) {
  const std::string exe = executable.empty() ? self_executable() : executable;
  const std::string stderr_path = (fs::path(dir) / ".plot_stderr.txt").string();
  std::vector<std::string> argv = {exe, "plot", dir};
  const fs::path methods = fs::path(dir) / "methods.yaml";
  if (fs::exists(methods)) argv.insert(argv.end(), {"--methods-file", methods.string()});
  const ProcessResult result = run_process(argv, stderr_path);
  const std::string failure = result.ok() ? "" : describe_failure(result, stderr_path);
  std::error_code ec;
  fs::remove(stderr_path, ec);
  return failure;
}

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
