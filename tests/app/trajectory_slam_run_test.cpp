// `msislab run --method robocentric|worldcentric` end to end. On the simulated replica (seed 42,
// read through its raw profiles, the segments of config/stpere_replica.yaml; the detections path
// with that config is the README's, held by tests/app/claims_test.cpp and
// claims_montecarlo_test.cpp): both write the result files per interfaces.md, match scans, and
// their mean error is below dead reckoning's (well below in the loop area) and below stated bounds,
// overall and in the canal (the paper's Table I). The two trajectory parameterisations of the same
// IEKF agree to a centimetre, on both datasets. On the real St. Pere dataset (skipped without it):
// the loop area improves on dead reckoning and the whole run does not regress past a stated bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "method_summary_lookup.hpp"
#include "results/results.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing_lookup::diagnostic;

double segment(const RunMetrics& m, const std::string& name) {
  for (const auto& [n, value] : m.segments) {
    if (n == name && value) return *value;
  }
  ADD_FAILURE() << "no segment " << name;
  return 0.0;
}

/// What the tests read of matches.csv: rows, accepted rows, rows with a truth, and the sum of
/// the accepted rows' NEES.
struct MatchesCsv {
  int rows = 0, accepted = 0, with_truth = 0;
  double accepted_nees_sum = 0.0;
};

/// How many independent scans a run's NEES series is worth: N / (1 + 2 sum_k rho_k), rho_k its
/// autocorrelation at lag k, summed while it stays positive (Geyer's initial positive sequence).
double effective_scans(const std::vector<results::NeesSample>& samples) {
  const double n = static_cast<double>(samples.size());
  double mean = 0.0;
  for (const results::NeesSample& s : samples) mean += s.nees / n;
  const auto covariance = [&](std::size_t lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i + lag < samples.size(); ++i)
      sum += (samples[i].nees - mean) * (samples[i + lag].nees - mean);
    return sum / n;
  };
  const double variance = covariance(0);
  double sum_rho = 0.0;
  for (std::size_t lag = 1; lag < samples.size(); ++lag) {
    const double rho = covariance(lag) / variance;
    if (rho <= 0.0) break;
    sum_rho += rho;
  }
  return n / (1.0 + 2.0 * sum_rho);
}

MatchesCsv read_matches_csv(const fs::path& path) {
  MatchesCsv out;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("t_s,scan,reference,t_reference_s,distance_m,outcome,", 0), 0u) << line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    if (line.back() == ',') fields.emplace_back();
    EXPECT_EQ(fields.size(), 31u) << line;
    if (fields.size() != 31u) continue;
    ++out.rows;
    out.with_truth += !fields[27].empty();
    if (fields[5] == "accepted") {
      ++out.accepted;
      out.accepted_nees_sum += fields[30].empty() ? 0.0 : std::stod(fields[30]);
    }
  }
  return out;
}

/// The two parameterisations are one estimate up to linearisation: at today's noise the
/// linearisation error is 1e-4 of a NEES and single runs agree to a millimetre; centimetres apart
/// only at heading noises far beyond today's, within the Monte Carlo noise (docs/robocentric.md).
/// So their mean errors on one dataset differ by under 1 cm, either way: a larger gap is a bug in
/// one of them, not noise.
void expect_parameterisations_agree(const RunMetrics& robocentric, const RunMetrics& worldcentric) {
  const double rc_minus_wc_m = robocentric.errors.mean_m - worldcentric.errors.mean_m;
  std::cout << "robocentric - world-centric mean error: " << rc_minus_wc_m << " m\n";
  EXPECT_NEAR(rc_minus_wc_m, 0.0, 0.01);
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
  // The raw profiles, not the detections that config/stpere_replica.yaml reads (the main job's
  // path, scored over 50 seeds in docs/results.md): here the front end sees the echoes' peaks.
  const std::string config = tmp.file("replica_raw.yaml");
  testing::write_text(config,
                      "segmentation: {source: raw}\n"
                      "segments: {loop: [0, 2000], canal: [2000, 3400], exit: [2900, 3400]}\n");
  simulate({std::string(MSISLAB_SOURCE_DIR) + "/scenarios/stpere_replica.yaml", dataset,
            std::nullopt, 2});
  const RunOutcome dr = run({dataset, "deadreckoning", tmp.file("dr"), config});
  const RunOutcome wc = run({dataset, "worldcentric", tmp.file("wc"), config});
  const RunOutcome rc = run({dataset, "robocentric", tmp.file("rc"), config});
  ASSERT_TRUE(dr.metrics && wc.metrics && rc.metrics);
  for (const RunOutcome* r : {&dr, &wc, &rc}) print("replica", *r->metrics);
  // Measured (seed 42, the shipped replica: the retraced mesh, the echo shape of
  // docs/simulator.md, the sonar stopping at 3020 s and the vehicle pointing where the real one
  // did; raw profiles): robocentric 1.639 m (loop 1.01, canal 2.58), ANEES 3.78, 596 matches
  // accepted, world-centric the same to 1e-3 m; dead reckoning 4.27 m (loop 2.75, canal 6.53).
  // The replica before the heading history (the vehicle pointing along its path) gave robocentric
  // 2.736 m (loop 1.69, canal 4.30), ANEES 7.69, against dead reckoning's 3.59 m. The ratios to
  // dead reckoning depend on its drift, one random walk per run (seeds 43-45 then: 1.38-2.62 m
  // against 6.0-11.4 m); the absolute bounds keep the test sensitive to a SLAM regression that a
  // lucky dead reckoning would hide. The bounds sit 20-50 % above seed 42's figures; the history
  // of these figures is in docs/trajectory_slam.md ("Results").
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_GT(m.matches_accepted, m.scans);
    ASSERT_TRUE(m.anees);
    EXPECT_LT(m.errors.mean_m, 0.6 * dr.metrics->errors.mean_m) << m.method;          // 0.38
    EXPECT_LT(m.errors.mean_m, 2.0) << m.method;                                      // 1.64
    EXPECT_LT(segment(m, "loop"), 0.5 * segment(*dr.metrics, "loop")) << m.method;    // 0.37
    EXPECT_LT(segment(m, "canal"), 0.6 * segment(*dr.metrics, "canal")) << m.method;  // 0.39
    EXPECT_LT(segment(m, "canal"), 3.2) << m.method;                                  // 2.58
    // One run's ANEES over 218 correlated scans: 3.78 (7.69 before the heading history; one-way
    // association: 14). Below: the statistic is the mean of the run's NEES, worth N_eff
    // independent chi-square(3) draws (effective_scans, from its own autocorrelation), so a
    // consistent filter's ANEES lies above the 2.5 % quantile of chi-square(3 N_eff) / N_eff
    // (false alarm 2.5 %); an ANEES under it means covariances blown up. The widest case, every
    // scan one variable (0.216), could hardly fail.
    const std::string dir = slam == &wc ? "wc" : "rc";
    const double n_eff =
        effective_scans(results::read_nees_csv((fs::path(tmp.file(dir)) / "nees.csv").string()));
    const double lower = average_chi2_bounds(std::max(1, static_cast<int>(n_eff)), 3).first;
    std::cout << m.method << ": ANEES " << *m.anees << " over " << n_eff
              << " effective scans, lower bound " << lower << "\n";
    EXPECT_LT(*m.anees, 5.0) << m.method;
    EXPECT_GT(*m.anees, lower) << m.method;
  }
  expect_parameterisations_agree(*rc.metrics, *wc.metrics);  // measured 0.0002 m
  for (const char* dir : {"wc", "rc"}) {
    for (const char* file :
         {"trajectory.tum", "scans.csv", "matches.csv", "map.ply", "metrics.json"}) {
      EXPECT_TRUE(fs::is_regular_file(fs::path(tmp.file(dir)) / file)) << dir << "/" << file;
    }
  }
  // matches.csv: a row per candidate, as many accepted as the metrics count, every row with the
  // simulation's true relative pose; the accepted matches' NEES against it averages near 3 (the
  // spIC covariance is honest to within a factor of about 2; measured 5.5 with the shipped model).
  const MatchesCsv matches = read_matches_csv(fs::path(tmp.file("rc")) / "matches.csv");
  EXPECT_EQ(static_cast<double>(matches.rows), rc.metrics->diagnostics.at(0).second);  // candidates
  EXPECT_EQ(matches.accepted, rc.metrics->matches_accepted);
  EXPECT_EQ(matches.with_truth, matches.rows);
  ASSERT_GT(matches.accepted, 0);
  EXPECT_LT(matches.accepted_nees_sum / matches.accepted, 12.0);
  // Consecutive matches against the simulation truth (docs/formats.md, metrics.json): dead
  // reckoning's translations are unbiased (measured 1.007); spIC's, from the raw profiles' peaks,
  // nearly so (0.985 with the earlier echo model). From the detections, where a reading is the
  // centre of the nearest detected run, spIC shortens them a little more (docs/simulator.md,
  // "Scan-match scale").
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_NEAR(diagnostic(m, "consecutive_dead_reckoning_scale"), 1.0, 0.03) << m.method;
    EXPECT_NEAR(diagnostic(m, "consecutive_match_scale"), 0.995, 0.035) << m.method;
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
  expect_parameterisations_agree(*rc.metrics, *wc.metrics);  // measured -0.0008 m
  // Measured: robocentric 2.84 m (loop 1.74, canal 4.47), 520 of 601 matches accepted, dead
  // reckoning 3.56 m (3.17, 4.13); the paper: 1.15 m and 2.05 m. The canal is still worse than
  // dead reckoning (docs/trajectory_slam.md). Before the sonar clock offset (0.66 s, estimated
  // from the sensors, docs/simulator.md) 2.95 m (loop 1.53, canal 5.07), 420 of 599 accepted;
  // the loop's ratio to dead reckoning is 0.55 now (0.49 then) against the bound 0.6. One-way
  // association gave 3.99 m (1.37, 7.89).
  // GPS gives no pose truth: matches.csv has a row per candidate and empty truth columns.
  const MatchesCsv matches = read_matches_csv(fs::path(tmp.file("rc")) / "matches.csv");
  EXPECT_EQ(static_cast<double>(matches.rows), rc.metrics->diagnostics.at(0).second);  // candidates
  EXPECT_EQ(matches.accepted, rc.metrics->matches_accepted);
  EXPECT_EQ(matches.with_truth, 0);
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_GT(m.scans, 200);
    EXPECT_LT(segment(m, "loop"), 0.6 * segment(*dr.metrics, "loop")) << m.method;  // 0.55
    EXPECT_LT(m.errors.mean_m, 0.95 * dr.metrics->errors.mean_m) << m.method;       // 0.80
  }
  // Consecutive matches against the GPS (which reads them about 2 % low: its noise lengthens the
  // true displacement, docs/simulator.md): measured dead reckoning 0.995, spIC 1.024. The real
  // matches do not shorten the motion as the replica's (0.920 against its own GPS) do.
  for (const RunOutcome* slam : {&wc, &rc}) {
    const RunMetrics& m = *slam->metrics;
    EXPECT_NEAR(diagnostic(m, "consecutive_dead_reckoning_scale"), 0.995, 0.025) << m.method;
    EXPECT_NEAR(diagnostic(m, "consecutive_match_scale"), 1.024, 0.03) << m.method;
  }
}

}  // namespace
}  // namespace msislab::app
