#include "app/montecarlo_command.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/cli.hpp"
#include "app/directory_lock.hpp"
#include "app/methods.hpp"
#include "app/montecarlo_directory.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "app/run_command.hpp"
#include "app/worker_processes.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "io/montecarlo_files.hpp"
#include "io/scenario_yaml.hpp"
#include "io/sim_dataset.hpp"
#include "io/text_lines.hpp"
#include "sim/scene.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

std::string absolute(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

void check_methods(const std::vector<std::string>& methods) {
  if (methods.empty()) throw io::InputError("--methods: no method given");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    method_info(methods[i], "--methods");
    if (std::find(methods.begin(), methods.begin() + static_cast<long>(i), methods[i]) !=
        methods.begin() + static_cast<long>(i)) {
      throw io::InputError("--methods '" + methods[i] + "': given twice");
    }
  }
}

/// What the workers share: the directory's settings and the inputs read once by the caller.
struct RunContext {
  io::MonteCarloManifest manifest;
  std::string dir;
  sim::Scenario scenario;
  std::string scenario_text;
  sim::TriangleMesh mesh;
  SlamConfig config;
  int simulation_threads = 1;
  bool keep_datasets = false;
};

/// Reads and checks every input and locks the directory; then makes or resumes it: scenario.yaml
/// and config.yaml copies, montecarlo.json.
RunContext prepare(const MonteCarloOptions& options, std::optional<DirectoryLock>& lock) {
  check_methods(options.methods);
  RunContext ctx;
  io::MonteCarloManifest& manifest = ctx.manifest;
  check_shard_and_jobs(options.shard, options.jobs, manifest.shard_index, manifest.shard_count);
  if (options.runs < 1) {
    throw io::InputError("--runs " + std::to_string(options.runs) + ": must be at least 1");
  }
  ctx.scenario = io::read_scenario(options.scenario_path);
  if (!fs::is_regular_file(ctx.scenario.scene.mesh_path)) {
    io::fail_file(options.scenario_path,
                  "key 'scene.mesh': '" + ctx.scenario.scene.mesh_path + "' does not exist");
  }
  const io::MeshMaterials materials{ctx.scenario.scene.default_material,
                                    ctx.scenario.scene.group_materials};
  ctx.mesh = io::read_mesh(ctx.scenario.scene.mesh_path, materials);
  if (!options.config_path.empty()) ctx.config = io::read_slam_config(options.config_path);
  ctx.scenario_text = io::read_whole_file(options.scenario_path);
  const std::string config_text =
      options.config_path.empty() ? "" : io::read_whole_file(options.config_path);
  manifest.executable_digest = executable_digest(self_executable());

  lock.emplace(options.out_dir, "msislab montecarlo " + options.scenario_path);
  check_resumable(options.out_dir, ctx.scenario_text, !options.config_path.empty(), config_text,
                  options.scenario_path, manifest.executable_digest);
  manifest.scenario_source = absolute(options.scenario_path);
  manifest.first_seed = ctx.scenario.seed;
  manifest.runs = options.runs;
  manifest.methods = options.methods;
  manifest.has_config = !options.config_path.empty();
  write_directory_header(options.out_dir, manifest, ctx.scenario_text, config_text);
  ctx.dir = options.out_dir;
  ctx.keep_datasets = options.keep_datasets;
  return ctx;
}

/// DIR/runs/<method>/.run_<rrrr>.partial: where a run's result is written before it is put in
/// place, so a run directory is never half-written.
std::string partial_dir(const std::string& dir, const std::string& method, int run) {
  return (fs::path(dir) / "runs" / method / ("." + run_name(run) + ".partial")).string();
}

/// Fills the partial directory of (method, run) with `write`, then puts it in place of the run
/// directory.
void put_in_place(const std::string& dir, const std::string& method, int run,
                  const std::function<void(const std::string&)>& write) {
  const std::string partial = partial_dir(dir, method, run);
  std::error_code ec;
  fs::remove_all(partial, ec);
  io::create_output_dir(partial);
  write(partial);
  const std::string target = run_dir(dir, method, run);
  fs::remove_all(target, ec);
  fs::rename(partial, target, ec);
  if (ec) io::fail_file(target, "cannot put the run's results in place: " + ec.message());
}

/// Records that a method did not finish run r: a run directory holding only failed.json.
void record_failure(const std::string& dir, const std::string& method,
                    const io::RunFailure& failure) {
  put_in_place(dir, method, failure.run, [&](const std::string& out) {
    io::write_failure_json((fs::path(out) / "failed.json").string(), failure);
  });
}

std::string scratch_file(const std::string& dir, int run, const char* suffix) {
  return (fs::path(dir) / "scratch" / (run_name(run) + suffix)).string();
}

/// The worker's note of what it is doing (the last line names the stage a crash hit).
void note_stage(const std::string& dir, int run, const std::string& stage) {
  std::ofstream(scratch_file(dir, run, ".stage"), std::ios::app) << stage << "\n" << std::flush;
}

/// Test hook (docs/cli.md): MSISLAB_MONTECARLO_FAULTS="run:where:how,..." makes the worker of
/// run `run` crash (SIGSEGV) or throw at `where` ("simulate" or a method name).
void injected_fault(int run, const std::string& where) {
  const char* faults = std::getenv("MSISLAB_MONTECARLO_FAULTS");
  if (faults == nullptr) return;
  std::istringstream list(faults);
  for (std::string entry; std::getline(list, entry, ',');) {
    const std::string prefix = std::to_string(run) + ":" + where + ":";
    if (entry.rfind(prefix, 0) != 0) continue;
    const std::string how = entry.substr(prefix.size());
    if (how == "crash") {
      const rlimit no_core{0, 0};  // an injected crash leaves no core file behind
      ::setrlimit(RLIMIT_CORE, &no_core);
      std::raise(SIGSEGV);
    }
    if (how == "throw") throw std::runtime_error("injected failure (MSISLAB_MONTECARLO_FAULTS)");
  }
}

/// Worker process of run r: simulates into memory, runs the pending methods on the dataset and
/// puts each method's result (or its failed.json) in place.
int execute_run(const RunContext& ctx, int run, const std::vector<std::string>& pending) {
  // The worker's stderr goes to a file, whose last line explains a crash.
  const int err = ::open(scratch_file(ctx.dir, run, ".stderr").c_str(),
                         O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (err >= 0) ::dup2(err, STDERR_FILENO);
  const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  std::shared_ptr<const io::DatasetRecords> records;
  std::string dataset_label;
  try {
    note_stage(ctx.dir, run, "simulate");
    sim::Scenario scenario = ctx.scenario;
    scenario.seed = seed;
    const sim::Scene scene(ctx.mesh, scenario.scene.surface);
    injected_fault(run, "simulate");
    const sim::SimulationResult result = sim::simulate(scenario, scene, ctx.simulation_threads);
    records = std::make_shared<const io::DatasetRecords>(io::simulated_records(scenario, result));
    dataset_label = records->name;
    if (ctx.keep_datasets) {
      dataset_label = absolute((fs::path(ctx.dir) / "datasets" / run_name(run)).string());
      io::write_simulated_dataset(dataset_label, scenario, result, ctx.scenario_text);
    }
  } catch (const std::exception& e) {
    for (const std::string& method : pending) {
      record_failure(ctx.dir, method, {run, seed, "simulate", e.what()});
    }
    return 0;
  }
  std::optional<RunInputs> in;
  SharedInputs shared;
  for (const std::string& method : pending) {
    try {
      note_stage(ctx.dir, run, "run");
      if (!in) in = run_inputs_of(records, ctx.config);
      injected_fault(run, method);
      const MethodResult result = run_method(method, *in, &shared);
      if (!result.metrics) throw io::InputError("no metrics (no truth in the dataset?)");
      // The summary needs neither the map nor the dataset; the map is large.
      put_in_place(ctx.dir, method, run, [&](const std::string& out) {
        write_method_result(out, result, dataset_label, /*write_map=*/false);
        io::write_errors_csv((fs::path(out) / "errors.csv").string(), result.errors,
                             result.t_first_truth_s);
      });
    } catch (const std::exception& e) {
      record_failure(ctx.dir, method, {run, seed, "run", e.what()});
    }
  }
  return 0;
}

/// The last line of the worker's stage notes ("simulate" or "run"); "simulate" when there is none.
std::string crashed_stage(const std::string& dir, int run) {
  const std::string last = io::last_line(scratch_file(dir, run, ".stage"));
  return last.empty() ? "simulate" : last;
}

/// Removes what workers left half-written: partial run directories and datasets, scratch files.
void remove_leftovers(const std::string& dir, const std::vector<std::string>& methods,
                      std::optional<int> run = std::nullopt) {
  std::error_code ec;
  for (const std::string& method : methods) {
    const fs::path folder = fs::path(dir) / "runs" / method;
    if (!fs::is_directory(folder)) continue;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      const bool partial = name.size() > 8 && name.compare(name.size() - 8, 8, ".partial") == 0;
      if (partial && (!run || name == "." + run_name(*run) + ".partial")) {
        fs::remove_all(entry.path(), ec);
      }
    }
  }
  const fs::path datasets = fs::path(dir) / "datasets";
  if (fs::is_directory(datasets)) {
    for (const auto& entry : fs::directory_iterator(datasets, ec)) {
      const std::string name = entry.path().filename().string();
      const std::string hidden = run ? "." + run_name(*run) + "." : ".";
      if (name.rfind(hidden, 0) == 0) fs::remove_all(entry.path(), ec);
    }
  }
  if (run) {
    for (const char* suffix : {".stderr", ".stage"})
      fs::remove(scratch_file(dir, *run, suffix), ec);
  } else {
    fs::remove_all(fs::path(dir) / "scratch", ec);
  }
}

bool finished(const std::string& dir, const std::string& method, int run) {
  return fs::exists(fs::path(run_dir(dir, method, run)) / "metrics.json");
}

}  // namespace

void check_shard_and_jobs(const std::string& shard, int jobs, int& shard_index, int& shard_count) {
  shard_index = 0;
  shard_count = 1;
  if (!shard.empty() && !io::parse_shard(shard, shard_index, shard_count)) {
    throw io::InputError("--shard '" + shard + "': expected i/N with 0 <= i < N");
  }
  if (jobs < 0) {
    throw io::InputError("--jobs " + std::to_string(jobs) + ": must be 0 (default) or more");
  }
}

MonteCarloOutcome montecarlo(const MonteCarloOptions& options, const MonteCarloLog& log) {
  std::optional<DirectoryLock> lock;
  RunContext ctx = prepare(options, lock);
  const std::string& dir = ctx.dir;
  const std::vector<int> runs = runs_of(ctx.manifest);
  remove_leftovers(dir, ctx.manifest.methods);  // of a command killed outright

  struct Pending {
    int run;
    std::vector<std::string> methods;
  };
  std::vector<Pending> todo;
  for (const int r : runs) {
    std::vector<std::string> methods;
    for (const std::string& m : ctx.manifest.methods) {
      if (!finished(dir, m, r)) methods.push_back(m);
    }
    if (!methods.empty()) todo.push_back({r, methods});
  }
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Several runs at once: one simulation thread each, so that J runs keep J cores busy.
  ctx.simulation_threads =
      std::min(static_cast<std::size_t>(jobs), todo.size()) > 1
          ? 1
          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // The shared parent folders are made here, not by the workers at the same time.
  io::create_output_dir((fs::path(dir) / "scratch").string());
  for (const std::string& m : ctx.manifest.methods) {
    io::create_output_dir((fs::path(dir) / "runs" / m).string());
  }
  if (ctx.keep_datasets) io::create_output_dir((fs::path(dir) / "datasets").string());

  MonteCarloOutcome outcome;
  outcome.runs = runs.size();
  Progress progress(runs.size(), runs.size() - todo.size(), log.terminal, log.log);
  progress.redraw();
  WorkerPool pool;
  pool.workers = jobs;
  const int lock_fd = lock->fd();
  pool.job = [&](std::size_t i) {
    ::close(lock_fd);  // the lock is the caller's alone
    return execute_run(ctx, todo[i].run, todo[i].methods);
  };
  pool.finished = [&](std::size_t i, const ProcessResult& result) {
    const int r = todo[i].run;
    const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(r);
    bool failed = false;
    for (const std::string& method : todo[i].methods) {
      if (finished(dir, method, r)) continue;
      failed = true;
      const bool recorded = fs::exists(fs::path(run_dir(dir, method, r)) / "failed.json");
      if (!result.ok() || !recorded) {
        record_failure(dir, method,
                       {r, seed, crashed_stage(dir, r),
                        describe_failure(result, scratch_file(dir, r, ".stderr"))});
      }
    }
    ++outcome.executed;
    remove_leftovers(dir, ctx.manifest.methods, r);
    progress.run_finished(failed);
  };
  pool.tick = [&] { progress.redraw(); };
  pool.stopped = [&](std::size_t i) { remove_leftovers(dir, ctx.manifest.methods, todo[i].run); };
  outcome.interrupted = run_worker_processes(todo.size(), pool);
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
  const ProcessResult result = run_process({exe, "plot", dir}, stderr_path);
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

/// `montecarlo` or `montecarlo merge`; the exit status (128 + the signal when stopped).
int run_montecarlo_cli(const MonteCarloCli& cli) {
  if (cli.command->got_subcommand("merge")) {
    print_montecarlo(merge_montecarlo(cli.merge), cli.merge.out_dir, true);
    if (!cli.no_plot) draw_and_list_figures("montecarlo", cli.merge.out_dir);
    return 0;
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
  return 0;
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
                 "one thread)");
  mc->add_option("--config,-c", options.config_path, "SLAM config YAML for every run");
  mc->add_option("--shard", options.shard,
                 "i/N: only the runs r with r % N == i (0 <= i < N); merge the shards afterwards");
  mc->add_flag("--keep-datasets", options.keep_datasets,
               "Also write each run's simulated dataset to DIR/datasets/run_<rrrr> (about 70 MB "
               "each on the St. Pere replica)");
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
