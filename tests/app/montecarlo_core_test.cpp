// The Monte Carlo machinery without the simulator: the worker processes (every job once in its
// own process, never more than the workers at a time, crashes contained, stop requests obeyed),
// the progress line, child processes and how their
// failures are described, and the run layout.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <atomic>
#include <chrono>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/montecarlo_directory.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "app/worker_processes.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

using testing::TempDir;

/// Files in dir whose name starts with prefix.
int count_files(const std::string& dir, const std::string& prefix) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    n += entry.path().filename().string().rfind(prefix, 0) == 0;
  }
  return n;
}

TEST(WorkerProcesses, EveryJobOnceInItsOwnProcessWithBoundedConcurrency) {
  const TempDir tmp;
  const std::string dir = tmp.path().string();
  WorkerPool pool;
  pool.workers = 3;
  pool.job = [&](std::size_t i) {
    // Marks itself running, records how many were, and its process.
    const std::string running = dir + "/running_" + std::to_string(i);
    testing::write_text(running, "");
    const int now = count_files(dir, "running_");
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    testing::write_text(dir + "/done_" + std::to_string(i),
                        std::to_string(now) + " " + std::to_string(::getpid()));
    std::filesystem::remove(running);
    return static_cast<int>(i % 4);
  };
  std::map<std::size_t, ProcessResult> results;
  pool.finished = [&](std::size_t i, const ProcessResult& r) { results[i] = r; };
  int ticks = 0;
  pool.tick = [&] { ++ticks; };
  pool.tick_period = std::chrono::milliseconds(5);
  EXPECT_EQ(run_worker_processes(12, pool), 0);
  ASSERT_EQ(results.size(), 12u);
  int peak = 0;
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_TRUE(results[i].exited) << i;
    EXPECT_EQ(results[i].exit_code, static_cast<int>(i % 4)) << i;
    std::istringstream done(testing::read_text(dir + "/done_" + std::to_string(i)));
    int running = 0;
    long pid = 0;
    done >> running >> pid;
    peak = std::max(peak, running);
    EXPECT_NE(pid, static_cast<long>(::getpid())) << i;
  }
  EXPECT_LE(peak, 3);
  EXPECT_GE(peak, 2);
  EXPECT_GT(ticks, 0);
  pool.job = [](std::size_t) -> int { std::abort(); };
  EXPECT_EQ(run_worker_processes(0, pool), 0);
}

TEST(WorkerProcesses, ACrashOrExceptionEndsOnlyItsOwnWorker) {
  WorkerPool pool;
  pool.workers = 2;
  pool.job = [](std::size_t i) {
    if (i == 1) {
      const rlimit no_core{0, 0};
      ::setrlimit(RLIMIT_CORE, &no_core);
      // The default action, as in a plain build: AddressSanitizer's handler (asan preset) would
      // turn the signal into a report and exit status 1.
      std::signal(SIGSEGV, SIG_DFL);
      std::raise(SIGSEGV);
    }
    if (i == 2) throw std::runtime_error("job 2");
    return 0;
  };
  std::map<std::size_t, ProcessResult> results;
  pool.finished = [&](std::size_t i, const ProcessResult& r) { results[i] = r; };
  EXPECT_EQ(run_worker_processes(4, pool), 0);
  ASSERT_EQ(results.size(), 4u);
  EXPECT_TRUE(results[0].ok());
  EXPECT_FALSE(results[1].exited);
  EXPECT_EQ(results[1].signal, SIGSEGV);
  EXPECT_TRUE(results[2].exited);
  EXPECT_EQ(results[2].exit_code, 70);
  EXPECT_TRUE(results[3].ok());
}

// A callback that throws in the caller ends every worker before the exception leaves the pool.
TEST(WorkerProcesses, AThrowingCallbackLeavesNoWorker) {
  const TempDir tmp;
  const std::string dir = tmp.path().string();
  WorkerPool pool;
  pool.workers = 2;
  pool.job = [&](std::size_t i) {
    // Written whole or not at all: the pool may end a worker the moment it starts (before its
    // pid is written), and a half-written file would read as no number.
    const std::string file = dir + "/pid_" + std::to_string(i);
    testing::write_text(file + ".partial", std::to_string(::getpid()));
    std::filesystem::rename(file + ".partial", file);
    if (i > 0) std::this_thread::sleep_for(std::chrono::seconds(30));
    return 0;
  };
  pool.finished = [](std::size_t, const ProcessResult&) { throw std::runtime_error("caller"); };
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(run_worker_processes(3, pool), std::runtime_error);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".partial") continue;  // ended before it wrote its pid
    const pid_t pid = std::stoi(testing::read_text(entry.path().string()));
    EXPECT_EQ(::kill(pid, 0), -1) << "worker " << pid << " still exists";
  }
  // The caller's signal mask is back: SIGTERM is not blocked.
  sigset_t mask;
  ::pthread_sigmask(SIG_SETMASK, nullptr, &mask);
  EXPECT_EQ(sigismember(&mask, SIGTERM), 0);
}

// A stop request (here job 0 sends SIGTERM to the pool's process) ends every running worker and
// starts no further job; the pool returns the signal and no worker is left.
TEST(WorkerProcesses, AStopRequestEndsEveryWorker) {
  const TempDir tmp;
  const std::string dir = tmp.path().string();
  const pid_t self = ::getpid();
  WorkerPool pool;
  pool.workers = 3;
  pool.job = [&](std::size_t i) {
    testing::write_text(dir + "/pid_" + std::to_string(i), std::to_string(::getpid()));
    if (i == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      ::kill(self, SIGTERM);
    }
    std::this_thread::sleep_for(std::chrono::seconds(30));
    return 0;
  };
  std::vector<std::size_t> stopped, finished;
  pool.stopped = [&](std::size_t i) { stopped.push_back(i); };
  pool.finished = [&](std::size_t i, const ProcessResult&) { finished.push_back(i); };
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(run_worker_processes(10, pool), SIGTERM);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_EQ(stopped.size(), 3u);
  EXPECT_TRUE(finished.empty());
  EXPECT_EQ(count_files(dir, "pid_"), 3);  // no job started after the request
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const pid_t pid = std::stoi(testing::read_text(entry.path().string()));
    EXPECT_EQ(::kill(pid, 0), -1) << "worker " << pid << " still exists";
    EXPECT_EQ(errno, ESRCH);
  }
}

TEST(Progress, PlainLinesWithElapsedAndEta) {
  EXPECT_EQ(format_duration(0.4), "0s");
  EXPECT_EQ(format_duration(45), "45s");
  EXPECT_EQ(format_duration(62), "1m02s");
  EXPECT_EQ(format_duration(3 * 3600 + 5 * 60 + 7), "3h05m");
  std::ostringstream out;
  Progress progress(50, 10, false, out);
  EXPECT_EQ(progress.line(), "montecarlo: 10/50 runs done, 0 failed, elapsed 0s, eta ?");
  progress.run_finished(true);
  progress.redraw();  // nothing on a plain log
  const std::string text = out.str();
  EXPECT_EQ(text.rfind("montecarlo: 11/50 runs done, 1 failed, elapsed 0s, eta ", 0), 0u) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

TEST(Progress, TerminalBarIsRedrawnInPlace) {
  std::ostringstream out;
  Progress progress(4, 0, true, out);
  progress.run_finished(false);
  progress.run_finished(false);
  progress.end();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 2);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
  EXPECT_NE(text.find("[###############...............] montecarlo: 2/4 runs done"),
            std::string::npos)
      << text;
}

TEST(Process, ExitStatusSignalAndLastStderrLine) {
  const TempDir tmp;
  const std::string err = tmp.file("err.txt");
  const ProcessResult ok = run_process({"/bin/sh", "-c", "echo out; exit 0"}, err);
  EXPECT_TRUE(ok.ok());
  const ProcessResult bad =
      run_process({"/bin/sh", "-c", "echo first >&2; echo 'msislab: bad' >&2; exit 3"}, err);
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(describe_failure(bad, err), "exit status 3: msislab: bad");
  const ProcessResult killed = run_process({"/bin/sh", "-c", "kill -9 $$"}, err);
  EXPECT_FALSE(killed.exited);
  EXPECT_EQ(killed.signal, 9);
  EXPECT_EQ(describe_failure(killed, err).rfind("killed by signal 9", 0), 0u);
  const ProcessResult missing = run_process({tmp.file("no_such_program")}, err);
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(describe_failure(missing, err).find("cannot start"), std::string::npos);
}

TEST(MonteCarloDirectory, RunLayoutAndShards) {
  EXPECT_EQ(run_name(7), "run_0007");
  EXPECT_EQ(run_name(12345), "run_12345");
  EXPECT_EQ(run_dir("mc", "worldcentric", 3), "mc/runs/worldcentric/run_0003");
  results::MonteCarloManifest manifest;
  manifest.runs = 7;
  EXPECT_EQ(runs_of(manifest), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  manifest.shard_index = 1;
  manifest.shard_count = 3;
  EXPECT_EQ(runs_of(manifest), (std::vector<int>{1, 4}));
  int index = 0, count = 0;
  EXPECT_TRUE(results::parse_shard("3/10", index, count));
  EXPECT_EQ(index, 3);
  EXPECT_EQ(count, 10);
  for (const char* bad : {"1", "2/2", "a/b", "-1/2", "1/0", "1/2/3", "1 /2", "+1/2", ""}) {
    EXPECT_FALSE(results::parse_shard(bad, index, count)) << bad;
  }
}

TEST(MonteCarloDirectory, ManifestRoundTrip) {
  const TempDir tmp;
  results::MonteCarloManifest m;
  m.scenario_source = "/a/b \"c\".yaml";
  m.first_seed = 18446744073709551615ull;  // 2^64 - 1: more digits than a double holds
  m.runs = 500;
  m.methods = {"deadreckoning", "worldcentric"};
  m.has_config = true;
  m.shard_index = 3;
  m.shard_count = 10;
  results::write_manifest_json(tmp.file("montecarlo.json"), m);
  const results::MonteCarloManifest r = results::read_manifest_json(tmp.file("montecarlo.json"));
  EXPECT_EQ(r.scenario_source, m.scenario_source);
  EXPECT_EQ(r.first_seed, m.first_seed);
  EXPECT_EQ(r.runs, 500);
  EXPECT_EQ(r.methods, m.methods);
  EXPECT_TRUE(r.has_config);
  EXPECT_EQ(r.shard_index, 3);
  EXPECT_EQ(r.shard_count, 10);
}

}  // namespace
}  // namespace msislab::app
