#include "app/montecarlo_runs.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "app/montecarlo_directory.hpp"
#include "app/montecarlo_worker.hpp"
#include "app/process.hpp"
#include "app/worker_processes.hpp"
#include "io/atomic_file.hpp"
#include "sim/scene.hpp"
#include "sim/simulator.hpp"
#include "sim/thread_pool.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

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
