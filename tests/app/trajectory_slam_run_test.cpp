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
  // Measured (seed 42): robocentric 0.886 m (loop 0.75, canal 1.08), ANEES 2.78; world-centric
  // the same to 1e-3 m; dead reckoning 6.28 m (loop 4.14, canal 9.22). With one-way spIC
  // association (before reciprocal became the default): 2.163 m (0.94, 3.84), ANEES 14.
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_GT(m.matches_accepted, m.scans);
    ASSERT_TRUE(m.anees);
    EXPECT_LT(m.errors.mean_m, 0.25 * dr.metrics->errors.mean_m) << m.method;          // 0.14
    EXPECT_LT(segment(m, "loop"), 0.3 * segment(*dr.metrics, "loop")) << m.method;     // 0.18
    EXPECT_LT(segment(m, "canal"), 0.25 * segment(*dr.metrics, "canal")) << m.method;  // 0.12
    // One run's ANEES over 236 correlated scans: 2.78 (one-way association: 14).
    EXPECT_LT(*m.anees, 5.0) << m.method;
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
  // Measured: robocentric 2.94 m (loop 1.57, canal 4.98), world-centric 2.94 m (1.57, 5.00),
  // dead reckoning 3.56 m (3.17, 4.13); the paper: 1.15 m and 2.05 m. The canal is still worse
  // than dead reckoning (docs/trajectory_slam.md). One-way association gave 3.99 m (1.37, 7.89).
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_LT(segment(m, "loop"), 0.6 * segment(*dr.metrics, "loop")) << m.method;  // 0.49
    EXPECT_LT(m.errors.mean_m, 0.95 * dr.metrics->errors.mean_m) << m.method;       // 0.83
  }
}

}  // namespace
}  // namespace msislab::app
