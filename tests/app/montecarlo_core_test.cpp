// The Monte Carlo machinery without the simulator: the job pool (every index once, never more
// than the workers at a time, errors passed on), the progress line, child processes and how their
// failures are described, and the run layout.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/montecarlo_directory.hpp"
#include "app/parallel_jobs.hpp"
#include "app/process.hpp"
#include "app/progress.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

using testing::TempDir;

TEST(ParallelJobs, EveryIndexOnceWithBoundedConcurrency) {
  std::mutex mutex;
  std::multiset<std::size_t> seen;
  std::atomic<int> running{0}, peak{0};
  int ticks = 0;
  run_parallel(
      20, 3,
      [&](std::size_t i) {
        const int now = ++running;
        int expected = peak.load();
        while (now > expected && !peak.compare_exchange_weak(expected, now)) {
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        --running;
        const std::lock_guard<std::mutex> lock(mutex);
        seen.insert(i);
      },
      [&] { ++ticks; }, std::chrono::milliseconds(2));
  ASSERT_EQ(seen.size(), 20u);
  for (std::size_t i = 0; i < 20; ++i) EXPECT_EQ(seen.count(i), 1u) << i;
  EXPECT_LE(peak.load(), 3);
  EXPECT_GE(peak.load(), 2);
  EXPECT_GT(ticks, 0);
  run_parallel(0, 4, [](std::size_t) { FAIL(); });
}

TEST(ParallelJobs, AThrowingJobStopsTheRestAndIsRethrown) {
  std::atomic<int> started{0};
  EXPECT_THROW(run_parallel(100, 1,
                            [&](std::size_t i) {
                              ++started;
                              if (i == 2) throw std::runtime_error("job 2");
                            }),
               std::runtime_error);
  EXPECT_EQ(started.load(), 3);
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
  io::MonteCarloManifest manifest;
  manifest.runs = 7;
  EXPECT_EQ(runs_of(manifest), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  manifest.shard_index = 1;
  manifest.shard_count = 3;
  EXPECT_EQ(runs_of(manifest), (std::vector<int>{1, 4}));
  int index = 0, count = 0;
  EXPECT_TRUE(io::parse_shard("3/10", index, count));
  EXPECT_EQ(index, 3);
  EXPECT_EQ(count, 10);
  for (const char* bad : {"1", "2/2", "a/b", "-1/2", "1/0", "1/2/3", "1 /2", "+1/2", ""}) {
    EXPECT_FALSE(io::parse_shard(bad, index, count)) << bad;
  }
}

TEST(MonteCarloDirectory, ManifestRoundTrip) {
  const TempDir tmp;
  io::MonteCarloManifest m;
  m.scenario_source = "/a/b \"c\".yaml";
  m.first_seed = 18446744073709551615ull;  // 2^64 - 1: more digits than a double holds
  m.runs = 500;
  m.methods = {"deadreckoning", "worldcentric"};
  m.has_config = true;
  m.shard_index = 3;
  m.shard_count = 10;
  io::write_manifest_json(tmp.file("montecarlo.json"), m);
  const io::MonteCarloManifest r = io::read_manifest_json(tmp.file("montecarlo.json"));
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
