#include "app/montecarlo_worker.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "app/external_method.hpp"
#include "app/method_result.hpp"
#include "app/montecarlo_directory.hpp"
#include "dataset/sim_dataset.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "settings/external_config.hpp"
#include "sim/scene.hpp"
#include "sim/simulator.hpp"

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

}  // namespace

/// Records that a method did not finish run r: a run directory holding only failed.json.
void record_failure(const std::string& dir, const std::string& method,
                    const results::RunFailure& failure) {
  put_in_place(dir, method, failure.run, [&](const std::string& out) {
    results::write_failure_json((fs::path(out) / "failed.json").string(), failure);
  });
}

std::string scratch_file(const std::string& dir, int run, const char* suffix) {
  return (fs::path(dir) / "scratch" / (run_name(run) + suffix)).string();
}

namespace {

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

bool is_external(const RunContext& ctx, const std::string& method) {
  return ctx.methods.at(method).kind == MethodKind::kExternal;
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
    dataset::write_simulated_dataset({files.dataset_dir, "dataset", "montecarlo", {}, false},
                                     scenario, result, ctx.scenario_text);
  }
  if (ctx.manifest.has_config && ctx.config.navigation_noise_from_dataset) {
    // The directory's config.yaml with the noise the runs took from the scenario (its sensors).
    files.config_path = io::absolute_path(scratch_file(ctx.dir, run, ".config.yaml"));
    settings::write_resolved_config(files.config_path, (fs::path(ctx.dir) / "config.yaml").string(),
                                    ctx.config.dead_reckoning);
  } else if (ctx.manifest.has_config) {
    files.config_path = io::absolute_path((fs::path(ctx.dir) / "config.yaml").string());
  } else {
    files.config_path = io::absolute_path(scratch_file(ctx.dir, run, ".config.yaml"));
    settings::write_dead_reckoning_config(files.config_path, ctx.config.dead_reckoning);
  }
  return files;
}

/// Runs one method of run r on the dataset and puts its result (or its failed.json) in place.
void run_one_method(const RunContext& ctx, int run, const std::string& method,
                    const dataset::RunInputs& in, SharedInputs& shared, const ExternalFiles* files,
                    const std::string& dataset_label) {
  const std::uint64_t seed = ctx.manifest.first_seed + static_cast<std::uint64_t>(run);
  ExternalSetup setup;
  if (files) {
    setup = {files->dataset_dir, files->config_path, seed,
             scratch_file(ctx.dir, run, ("." + method).c_str())};
  }
  try {
    injected_fault(run, method);
    const MethodResult result =
        run_method(ctx.methods.at(method), in, &shared, files ? &setup : nullptr);
    if (!result.metrics) throw io::InputError("no metrics (no truth in the dataset?)");
    // The summary needs neither the map nor the dataset; the map is large.
    put_in_place(ctx.dir, method, run, [&](const std::string& out) {
      write_method_result(out, result, dataset_label, /*write_map=*/false);
      results::write_errors_csv((fs::path(out) / "errors.csv").string(), result.errors,
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
  std::shared_ptr<const dataset::DatasetRecords> records;
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
  out.records =
      std::make_shared<const dataset::DatasetRecords>(dataset::simulated_records(scenario, result));
  out.dataset_label = out.records->name;
  std::string kept;
  if (ctx.keep_datasets) {
    out.dataset_label =
        io::absolute_path((fs::path(ctx.dir) / "datasets" / run_name(run)).string());
    dataset::write_simulated_dataset({out.dataset_label, "dataset", "montecarlo", {}, false},
                                     scenario, result, ctx.scenario_text);
    kept = out.dataset_label;
  }
  if (std::any_of(pending.begin(), pending.end(),
                  [&](const std::string& m) { return is_external(ctx, m); })) {
    try {
      out.files = external_files(ctx, run, scenario, result, kept);
    } catch (const std::exception& e) {
      out.files_failure = std::string("writing the dataset for external methods: ") + e.what();
    }
  }
  return out;
}

}  // namespace

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
  std::optional<dataset::RunInputs> in;
  SharedInputs shared;
  for (const std::string& method : pending) {
    note_stage(ctx.dir, run, "run");
    const bool external = is_external(ctx, method);
    if (external && !files) {
      record_failure(ctx.dir, method, {run, seed, "simulate", simulated.files_failure, {}});
      continue;
    }
    try {
      if (!in) in = dataset::run_inputs_of(simulated.records, ctx.config);
    } catch (const std::exception& e) {
      record_failure(ctx.dir, method, {run, seed, "run", e.what(), {}});
      continue;
    }
    run_one_method(ctx, run, method, *in, shared, external ? &*files : nullptr,
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

}  // namespace msislab::app
