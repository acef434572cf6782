#include "app/montecarlo_runs.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/external_method.hpp"
#include "app/method_result.hpp"
#include "app/montecarlo_directory.hpp"
#include "app/process.hpp"
#include "app/worker_processes.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/sim_dataset.hpp"
#include "io/text_lines.hpp"
#include "report/methods.hpp"
#include "sim/scene.hpp"
#include "sim/simulator.hpp"
#include "sim/thread_pool.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// Fills the partial directory of (method, run), DIR/runs/<method>/.run_<rrrr>.partial, with
/// `write`, then puts it in place of the run directory: a run directory is never half-written.
void put_in_place(const std::string& dir, const std::string& method, int run,
                  const std::function<void(const std::string&)>& write) {
  const std::string partial =
      (fs::path(dir) / "runs" / method / ("." + run_name(run) + ".partial")).string();
  std::error_code ec;
  fs::remove_all(partial, ec);
  io::create_output_dir(partial);
  write(partial);
  io::write_output_marker(partial, "result", "montecarlo", nullptr);
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
      std::signal(SIGSEGV, SIG_DFL);  // a signal death under AddressSanitizer's handler too
      std::raise(SIGSEGV);
    }
    if (how == "throw") throw std::runtime_error("injected failure (MSISLAB_MONTECARLO_FAULTS)");
  }
}

bool is_external(const std::string& method) {
  return report::method_info(method).kind == report::MethodKind::kExternal;
}

/// What an external method of run r is given: the dataset on disk (DIR/datasets/run_<rrrr> with
/// --keep-datasets, else written to DIR/scratch for this run only) and the SLAM config.
struct ExternalFiles {
  std::string dataset_dir;
  std::string config_path;
};

ExternalFiles external_files(const RunContext& ctx, int run, const sim::Scenario& scenario,
                             const sim::SimulationResult& result, const std::string& kept) {
  ExternalFiles files;
  files.dataset_dir = kept;
  if (files.dataset_dir.empty()) {
    files.dataset_dir = io::absolute_path(scratch_file(ctx.dir, run, ".dataset"));
    io::write_simulated_dataset({files.dataset_dir, "dataset", "montecarlo", {}, false}, scenario,
                                result, ctx.scenario_text);
  }
  if (ctx.manifest.has_config) {
    files.config_path = io::absolute_path((fs::path(ctx.dir) / "config.yaml").string());
  } else {
    files.config_path = io::absolute_path(scratch_file(ctx.dir, run, ".config.yaml"));
    io::write_dead_reckoning_config(files.config_path, ctx.config.dead_reckoning);
  }
  return files;
}

/// Runs one method of run r on the dataset and puts its result (or its failed.json) in place.
void run_one_method(const RunContext& ctx, int run, const std::string& method,
                    const io::RunInputs& in, SharedInputs& shared, const ExternalFiles* files,
                    const std::string& dataset_label) {
  const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  ExternalSetup setup;
  if (files) {
    setup = {files->dataset_dir, files->config_path, seed,
             scratch_file(ctx.dir, run, ("." + method).c_str())};
  }
  try {
    injected_fault(run, method);
    const MethodResult result = run_method(method, in, &shared, files ? &setup : nullptr);
    if (!result.metrics) throw io::InputError("no metrics (no truth in the dataset?)");
    // The summary needs neither the map nor the dataset; the map is large.
    put_in_place(ctx.dir, method, run, [&](const std::string& out) {
      write_method_result(out, result, dataset_label, /*write_map=*/false);
      io::write_errors_csv((fs::path(out) / "errors.csv").string(), result.errors,
                           result.t_first_truth_s);
    });
  } catch (const ExternalMethodError& e) {
    record_failure(ctx.dir, method, {run, seed, "run", e.what(), e.stderr_tail()});
  } catch (const std::exception& e) {
    record_failure(ctx.dir, method, {run, seed, "run", e.what(), {}});
  }
  std::error_code ec;
  if (files) fs::remove_all(setup.work_dir, ec);
}

/// What the worker of run r simulated: the dataset in memory, its label, and the files an
/// external method reads (or why they could not be written).
struct SimulatedRun {
  std::shared_ptr<const io::DatasetRecords> records;
  std::string dataset_label;
  std::optional<ExternalFiles> files;
  std::string files_failure;
};

/// Simulates run r into memory; on disk too with --keep-datasets, and for an external method.
/// Throws when the simulation fails.
SimulatedRun simulate_run(const RunContext& ctx, int run, const std::vector<std::string>& pending) {
  SimulatedRun out;
  note_stage(ctx.dir, run, "simulate");
  sim::Scenario scenario = ctx.scenario;
  scenario.seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  injected_fault(run, "simulate");
  const sim::SimulationResult result = [&] {
    if (ctx.trace) return sim::simulate(scenario, *ctx.trace, ctx.simulation_threads);
    const sim::Scene scene(ctx.mesh, scenario.scene.surface);
    return sim::simulate(scenario, scene, ctx.simulation_threads);
  }();
  out.records = std::make_shared<const io::DatasetRecords>(io::simulated_records(scenario, result));
  out.dataset_label = out.records->name;
  std::string kept;
  if (ctx.keep_datasets) {
    out.dataset_label =
        io::absolute_path((fs::path(ctx.dir) / "datasets" / run_name(run)).string());
    io::write_simulated_dataset({out.dataset_label, "dataset", "montecarlo", {}, false}, scenario,
                                result, ctx.scenario_text);
    kept = out.dataset_label;
  }
  if (std::any_of(pending.begin(), pending.end(), is_external)) {
    try {
      out.files = external_files(ctx, run, scenario, result, kept);
    } catch (const std::exception& e) {
      out.files_failure = std::string("writing the dataset for external methods: ") + e.what();
    }
  }
  return out;
}

/// Worker process of run r: simulates into memory, runs the pending methods on the dataset and
/// puts each method's result (or its failed.json) in place. The dataset is written to disk only
/// for an external method (or with --keep-datasets).
int execute_run(const RunContext& ctx, int run, const std::vector<std::string>& pending) {
  // The worker's stderr goes to a file, whose last line explains a crash.
  const int err = ::open(scratch_file(ctx.dir, run, ".stderr").c_str(),
                         O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (err >= 0) ::dup2(err, STDERR_FILENO);
  const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  SimulatedRun simulated;
  try {
    simulated = simulate_run(ctx, run, pending);
  } catch (const std::exception& e) {
    for (const std::string& method : pending) {
      record_failure(ctx.dir, method, {run, seed, "simulate", e.what(), {}});
    }
    return 0;
  }
  const std::optional<ExternalFiles>& files = simulated.files;
  std::optional<io::RunInputs> in;
  SharedInputs shared;
  for (const std::string& method : pending) {
    note_stage(ctx.dir, run, "run");
    if (is_external(method) && !files) {
      record_failure(ctx.dir, method, {run, seed, "simulate", simulated.files_failure, {}});
      continue;
    }
    try {
      if (!in) in = io::run_inputs_of(simulated.records, ctx.config);
    } catch (const std::exception& e) {
      record_failure(ctx.dir, method, {run, seed, "run", e.what(), {}});
      continue;
    }
    run_one_method(ctx, run, method, *in, shared, is_external(method) ? &*files : nullptr,
                   simulated.dataset_label);
  }
  std::error_code ec;
  if (files && !ctx.keep_datasets) fs::remove_all(files->dataset_dir, ec);
  return 0;
}

/// The last line of the worker's stage notes ("simulate" or "run"); "simulate" when there is none.
std::string crashed_stage(const std::string& dir, int run) {
  const std::string last = io::last_line(scratch_file(dir, run, ".stage"));
  return last.empty() ? "simulate" : last;
}

bool finished(const std::string& dir, const std::string& method, int run) {
  return fs::exists(fs::path(run_dir(dir, method, run)) / "metrics.json");
}

}  // namespace

void remove_leftovers(const std::string& dir, const std::vector<std::string>& methods,
                      std::optional<int> run) {
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
    // The worker's notes, and an external method's dataset, config and work folders.
    const fs::path scratch = fs::path(dir) / "scratch";
    const std::string own = run_name(*run) + ".";
    std::vector<fs::path> leftovers;
    for (const auto& entry : fs::directory_iterator(scratch, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(own, 0) == 0 || name.rfind("." + own, 0) == 0) leftovers.push_back(entry);
    }
    for (const fs::path& path : leftovers) fs::remove_all(path, ec);
  } else {
    fs::remove_all(fs::path(dir) / "scratch", ec);
  }
}

std::shared_ptr<const sim::ScenarioTrace> trace_once(const RunContext& ctx, int threads) {
  sim::ThreadPoolScope pool;  // the workers fork after this: no TBB thread may outlive it
  std::shared_ptr<const sim::ScenarioTrace> trace;
  try {
    const sim::Scene scene(ctx.mesh, ctx.scenario.scene.surface);
    trace = std::make_shared<const sim::ScenarioTrace>(
        sim::trace_scenario(ctx.scenario, scene, std::max(threads, 1)));
  } catch (const std::exception&) {
    trace = nullptr;
  }
  pool.finish();
  return trace;
}

std::vector<PendingRun> pending_runs(const RunContext& ctx, const std::vector<int>& runs) {
  std::vector<PendingRun> todo;
  for (const int r : runs) {
    std::vector<std::string> methods;
    for (const std::string& m : ctx.manifest.methods) {
      if (!finished(ctx.dir, m, r)) methods.push_back(m);
    }
    if (!methods.empty()) todo.push_back({r, methods});
  }
  return todo;
}

void make_run_folders(const RunContext& ctx) {
  io::create_output_dir((fs::path(ctx.dir) / "scratch").string());
  for (const std::string& m : ctx.manifest.methods) {
    io::create_output_dir((fs::path(ctx.dir) / "runs" / m).string());
  }
  if (ctx.keep_datasets) io::create_output_dir((fs::path(ctx.dir) / "datasets").string());
}

int execute_runs(const RunContext& ctx, const std::vector<PendingRun>& todo, int jobs, int lock_fd,
                 Progress& progress, std::size_t& executed) {
  const std::string& dir = ctx.dir;
  WorkerPool pool;
  pool.workers = jobs;
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
                       {r,
                        seed,
                        crashed_stage(dir, r),
                        describe_failure(result, scratch_file(dir, r, ".stderr")),
                        {}});
      }
    }
    ++executed;
    remove_leftovers(dir, ctx.manifest.methods, r);
    progress.run_finished(failed);
  };
  pool.tick = [&] { progress.redraw(); };
  pool.stopped = [&](std::size_t i) { remove_leftovers(dir, ctx.manifest.methods, todo[i].run); };
  return run_worker_processes(todo.size(), pool);
}

}  // namespace msislab::app
