// `msislab run --method robocentric|worldcentric` end to end. On the simulated replica (seed 42,
// config/stpere_replica.yaml): both write the result files per interfaces.md, match scans, and
// their mean error is well below dead reckoning's, overall and in the loop area and the canal
// (the paper's Table I). The two trajectory parameterisations of the same IEKF agree closely: the
// robocentric one must not be worse. On the real St. Pere dataset (skipped without it): the loop
// area improves on dead reckoning and the whole run does not regress past a stated bound.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;

double segment(const RunMetrics& m, const std::string& name) {
  for (const auto& [n, value] : m.segments) {
    if (n == name && value) return *value;
  }
  ADD_FAILURE() << "no segment " << name;
  return 0.0;
}

void print(const std::string& data, const RunMetrics& m) {
  std::cout << data << " " << m.method << ": mean " << m.errors.mean_m << " m (loop "
            << segment(m, "loop") << ", canal " << segment(m, "canal") << "), " << m.scans
            << " scans, " << m.matches_accepted << " matches accepted, ANEES "
            << m.anees.value_or(-1.0) << ", " << m.runtime_s << " s\n";
}

TEST(TrajectorySlamRun, ReplicaBothMethodsBeatDeadReckoning) {
  testing::TempDir tmp;
  const std::string dataset = tmp.file("replica");
  const std::string config = std::string(MSISLAB_SOURCE_DIR) + "/config/stpere_replica.yaml";
  simulate({std::string(MSISLAB_SOURCE_DIR) + "/scenarios/stpere_replica.yaml", dataset,
            std::nullopt, 2});
  const RunOutcome dr = run({dataset, "deadreckoning", tmp.file("dr"), config});
  const RunOutcome wc = run({dataset, "worldcentric", tmp.file("wc"), config});
  const RunOutcome rc = run({dataset, "robocentric", tmp.file("rc"), config});
  ASSERT_TRUE(dr.metrics && wc.metrics && rc.metrics);
  for (const RunOutcome* r : {&dr, &wc, &rc}) print("replica", *r->metrics);
  // Measured (seed 42): robocentric 2.163 m (loop 0.94, canal 3.84), world-centric 2.163 m
  // (0.94, 3.84), dead reckoning 6.28 m (loop 4.14, canal 9.22).
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_GT(m.matches_accepted, m.scans);
    ASSERT_TRUE(m.anees);
    EXPECT_LT(m.errors.mean_m, 0.5 * dr.metrics->errors.mean_m) << m.method;
    EXPECT_LT(segment(m, "loop"), 0.5 * segment(*dr.metrics, "loop")) << m.method;
    EXPECT_LT(segment(m, "canal"), 0.7 * segment(*dr.metrics, "canal")) << m.method;
  }
  EXPECT_LT(rc.metrics->errors.mean_m, wc.metrics->errors.mean_m + 0.02);
  for (const char* dir : {"wc", "rc"}) {
    for (const char* file : {"trajectory.tum", "scans.csv", "map.ply", "metrics.json"}) {
      EXPECT_TRUE(fs::is_regular_file(fs::path(tmp.file(dir)) / file)) << dir << "/" << file;
    }
  }
}

TEST(TrajectorySlamRun, RealStPere) {
  MSISLAB_REQUIRE_STPERE();
  testing::TempDir tmp;
  const std::string config = std::string(MSISLAB_SOURCE_DIR) + "/config/stpere.yaml";
  const RunOutcome dr = run({testing::stpere_dir(), "deadreckoning", tmp.file("dr"), config});
  const RunOutcome wc = run({testing::stpere_dir(), "worldcentric", tmp.file("wc"), config});
  const RunOutcome rc = run({testing::stpere_dir(), "robocentric", tmp.file("rc"), config});
  ASSERT_TRUE(dr.metrics && wc.metrics && rc.metrics);
  for (const RunOutcome* r : {&dr, &wc, &rc}) print("St. Pere", *r->metrics);
  // Measured: robocentric 3.99 m (loop 1.37, canal 7.89), world-centric 3.99 m (1.37, 7.88),
  // dead reckoning 3.56 m (3.17, 4.13); the paper: 1.15 m and 2.05 m. The canal's parallel walls
  // still pull the SLAM estimate along the canal (docs/trajectory_slam.md).
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_LT(segment(m, "loop"), 0.6 * segment(*dr.metrics, "loop")) << m.method;
    EXPECT_LT(m.errors.mean_m, 1.25 * dr.metrics->errors.mean_m) << m.method;
  }
}

}  // namespace
}  // namespace msislab::app
