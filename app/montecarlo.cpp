#include "app/montecarlo.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "app/directory_lock.hpp"
#include "app/montecarlo_directory.hpp"
#include "app/montecarlo_runs.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "results/montecarlo_files.hpp"
#include "settings/config_yaml.hpp"
#include "settings/scenario_scene.hpp"
#include "sim/navigation_sensors.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

void check_methods(const MethodCatalogue& catalogue, const std::vector<std::string>& methods) {
  if (methods.empty()) throw io::InputError("--methods: no method given");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    catalogue.at(methods[i], "--methods");
    if (std::find(methods.begin(), methods.begin() + static_cast<long>(i), methods[i]) !=
        methods.begin() + static_cast<long>(i)) {
      throw io::InputError("--methods '" + methods[i] + "': given twice");
    }
  }
}

/// Reads and checks every input and locks the directory; then makes or resumes it: scenario.yaml
/// and config.yaml copies, montecarlo.json.
RunContext prepare(const MonteCarloOptions& options, std::optional<DirectoryLock>& lock) {
  RunContext ctx;
  ctx.methods = MethodCatalogue::with_methods_file(options.methods_file);
  check_methods(ctx.methods, options.methods);
  results::MonteCarloManifest& manifest = ctx.manifest;
  check_shard_and_jobs(options.shard, options.jobs, manifest.shard_index, manifest.shard_count);
  if (options.runs < 1) {
    throw io::InputError("--runs " + std::to_string(options.runs) + ": must be at least 1");
  }
  settings::CheckedScenario checked = settings::read_checked_scenario(options.scenario_path);
  for (const std::string& warning : checked.warnings) std::cerr << "msislab: " << warning << '\n';
  ctx.scenario = std::move(checked.scenario);
  ctx.mesh = std::move(checked.mesh);
  // Every run's dataset carries the scenario's navigation noise; the config is made over it once.
  settings::DatasetConfig config = settings::slam_config_for_dataset(
      options.config_path,
      settings::navigation_noise_as_stored(sim::navigation_noise_of(ctx.scenario)), "the scenario");
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
  if (!shard.empty() && !results::parse_shard(shard, shard_index, shard_count)) {
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

}  // namespace msislab::app
