#include "app/montecarlo_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "app/montecarlo_directory.hpp"
#include "app/parallel_jobs.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "app/run_command.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/input_error.hpp"
#include "io/montecarlo_files.hpp"
#include "io/scenario_yaml.hpp"
#include "io/text_lines.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

std::string absolute(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

void check_methods(const std::vector<std::string>& methods) {
  if (methods.empty()) throw io::InputError("--methods: no method given");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    check_method(methods[i], "--methods");
    if (std::find(methods.begin(), methods.begin() + static_cast<long>(i), methods[i]) !=
        methods.begin() + static_cast<long>(i)) {
      throw io::InputError("--methods '" + methods[i] + "': given twice");
    }
  }
}

/// Reads and checks every input, and makes or resumes the directory: scenario.yaml and
/// config.yaml copies, montecarlo.json.
io::MonteCarloManifest prepare(const MonteCarloOptions& options, const std::string& executable) {
  check_methods(options.methods);
  io::MonteCarloManifest manifest;
  if (!options.shard.empty() &&
      !io::parse_shard(options.shard, manifest.shard_index, manifest.shard_count)) {
    throw io::InputError("--shard '" + options.shard + "': expected i/N with 0 <= i < N");
  }
  if (options.runs < 1) {
    throw io::InputError("--runs " + std::to_string(options.runs) + ": must be at least 1");
  }
  if (options.jobs < 0) {
    throw io::InputError("--jobs " + std::to_string(options.jobs) +
                         ": must be 0 (default) or more");
  }
  const sim::Scenario scenario = io::read_scenario(options.scenario_path);
  if (!fs::is_regular_file(scenario.scene.mesh_path)) {
    io::fail_file(options.scenario_path,
                  "key 'scene.mesh': '" + scenario.scene.mesh_path + "' does not exist");
  }
  if (!options.config_path.empty()) io::read_slam_config(options.config_path);
  if (::access(executable.c_str(), X_OK) != 0) {
    io::fail_file(executable, "not an executable msislab");
  }
  const std::string scenario_text = io::read_whole_file(options.scenario_path);
  const std::string config_text =
      options.config_path.empty() ? "" : io::read_whole_file(options.config_path);
  manifest.executable_digest = executable_digest(executable);
  check_resumable(options.out_dir, scenario_text, !options.config_path.empty(), config_text,
                  options.scenario_path, manifest.executable_digest);

  manifest.scenario_source = absolute(options.scenario_path);
  manifest.first_seed = scenario.seed;
  manifest.runs = options.runs;
  manifest.methods = options.methods;
  manifest.has_config = !options.config_path.empty();
  write_directory_header(options.out_dir, manifest, scenario_text, config_text);
  return manifest;
}

struct RunContext {
  const io::MonteCarloManifest& manifest;
  std::string dir;
  std::string executable;
  bool single_threaded_simulation;
};

/// Records that a method did not finish run r: failed.json, and no metrics.json left behind.
void record_failure(const std::string& result_dir, const io::RunFailure& failure) {
  io::create_output_dir(result_dir);
  std::error_code ec;
  fs::remove(fs::path(result_dir) / "metrics.json", ec);
  fs::remove(fs::path(result_dir) / "nees.csv", ec);
  io::write_failure_json((fs::path(result_dir) / "failed.json").string(), failure);
}

/// Runs one method on the simulated dataset; false when it failed (recorded).
bool run_method(const RunContext& ctx, const std::string& dataset, const std::string& method,
                int run, std::uint64_t seed) {
  const std::string out = run_dir(ctx.dir, method, run);
  io::create_output_dir(out);
  std::error_code ec;
  fs::remove(fs::path(out) / "failed.json", ec);
  const std::string stderr_path = (fs::path(out) / "stderr.txt").string();
  std::vector<std::string> args = {ctx.executable, "run",   dataset, "--method",
                                   method,         "--out", out};
  if (ctx.manifest.has_config) {
    args.insert(args.end(), {"--config", (fs::path(ctx.dir) / "config.yaml").string()});
  }
  const ProcessResult result = run_process(args, stderr_path);
  const bool finished = result.ok() && fs::exists(fs::path(out) / "metrics.json");
  if (!finished) {
    record_failure(out, {run, seed, "run",
                         result.ok() ? "no metrics.json written (no truth in the dataset?)"
                                     : describe_failure(result, stderr_path)});
    return false;
  }
  // The summary needs neither the map nor an empty error log; the map is large.
  fs::remove(fs::path(out) / "map.ply", ec);
  if (fs::is_empty(stderr_path, ec)) fs::remove(stderr_path, ec);
  return true;
}

/// Simulates run r into a scratch dataset, runs the pending methods on it and deletes the dataset.
/// Returns whether any method failed.
bool execute_run(const RunContext& ctx, int run, const std::vector<std::string>& pending) {
  const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  const fs::path scratch = fs::path(ctx.dir) / "scratch";
  const std::string dataset = (scratch / run_name(run)).string();
  const std::string stderr_path = (scratch / (run_name(run) + ".simulate.txt")).string();
  io::create_output_dir(scratch.string());
  std::vector<std::string> args = {
      ctx.executable, "simulate", ctx.manifest.scenario_source, "--out",
      dataset,        "--seed",   std::to_string(seed)};
  if (ctx.single_threaded_simulation) args.insert(args.end(), {"--threads", "1"});
  const ProcessResult simulated = run_process(args, stderr_path);
  bool failed = false;
  if (!simulated.ok()) {
    const std::string reason = describe_failure(simulated, stderr_path);
    for (const std::string& method : pending) {
      record_failure(run_dir(ctx.dir, method, run), {run, seed, "simulate", reason});
    }
    failed = true;
  } else {
    for (const std::string& method : pending) {
      failed |= !run_method(ctx, dataset, method, run, seed);
    }
  }
  std::error_code ec;
  fs::remove_all(dataset, ec);
  fs::remove(stderr_path, ec);
  return failed;
}

}  // namespace

MonteCarloOutcome montecarlo(const MonteCarloOptions& options, const MonteCarloLog& log) {
  const std::string executable =
      options.executable.empty() ? self_executable() : absolute(options.executable);
  const io::MonteCarloManifest manifest = prepare(options, executable);
  const std::string dir = options.out_dir;
  const std::vector<int> runs = runs_of(manifest);

  struct Pending {
    int run;
    std::vector<std::string> methods;
  };
  std::vector<Pending> todo;
  for (const int r : runs) {
    std::vector<std::string> methods;
    for (const std::string& m : manifest.methods) {
      if (!fs::exists(fs::path(run_dir(dir, m, r)) / "metrics.json")) methods.push_back(m);
    }
    if (!methods.empty()) todo.push_back({r, methods});
  }
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Several runs at once: one simulation thread each, so that J runs keep J cores busy.
  const RunContext ctx{manifest, dir, executable,
                       std::min(static_cast<std::size_t>(jobs), todo.size()) > 1};
  // The shared parent folders are made here, not by the workers at the same time.
  io::create_output_dir((fs::path(dir) / "scratch").string());
  for (const std::string& m : manifest.methods) {
    io::create_output_dir((fs::path(dir) / "runs" / m).string());
  }

  MonteCarloOutcome outcome;
  outcome.runs = runs.size();
  outcome.executed = todo.size();
  Progress progress(runs.size(), runs.size() - todo.size(), log.terminal, log.log);
  progress.redraw();
  run_parallel(
      todo.size(), jobs,
      [&](std::size_t i) {
        const bool failed = execute_run(ctx, todo[i].run, todo[i].methods);
        progress.run_finished(failed);
      },
      [&] { progress.redraw(); });
  progress.end();
  std::error_code ec;
  fs::remove(fs::path(dir) / "scratch", ec);  // only when empty

  outcome.summary = write_summary_files(dir, manifest, runs);
  outcome.failed = failed_runs(dir, manifest.methods, runs);
  return outcome;
}

std::string draw_montecarlo_figures(const std::string& dir, const std::string& executable) {
  const std::string exe = executable.empty() ? self_executable() : executable;
  const std::string stderr_path = (fs::path(dir) / ".plot_stderr.txt").string();
  const ProcessResult result = run_process({exe, "plot", dir}, stderr_path);
  const std::string failure = result.ok() ? "" : describe_failure(result, stderr_path);
  std::error_code ec;
  fs::remove(stderr_path, ec);
  return failure;
}

}  // namespace msislab::app
