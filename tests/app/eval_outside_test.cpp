// `msislab eval` on a trajectory from elsewhere: a folder with only trajectory.tum (and maybe
// scans.csv), in another frame and on another clock than the truth. --t-offset and --align se2
// recover a known shift, the errors then vanish, --name names the method, the counts agree, and
// bad input is one line with exit status 2.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/eval_command.hpp"
#include "app/run_command.hpp"
#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "results/results.hpp"
#include "synthetic_dataset.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;

const Pose2 kShift(30.0, -7.0, 12.0 * M_PI / 180.0);  // T_truth_estimate
constexpr double kOffset_s = 1e9;                     // t_truth = t_estimate + kOffset_s
constexpr double kDegPerRad = 180.0 / M_PI;

// NEES 0.3^2 / 0.09 + 0.4^2 / 0.04 + 0.01^2 / 1e-4 = 6 for every scan, in the truth's frame.
const Eigen::Vector3d kScanError(0.3, -0.4, 0.01);
const Eigen::Vector3d kScanVariance(0.09, 0.04, 1e-4);

// The 300 s synthetic truth and an outside result folder holding it seen in the frame kShift^-1
// and on a clock starting at 0: trajectory.tum and, with scans, scans.csv (a scan every 30 s off
// the truth by kScanError with covariance diag(kScanVariance) in the truth's frame).
struct Outside {
  TempDir tmp;
  std::vector<io::TumPose> truth =
      testing::write_synthetic_dataset(tmp.path() / "dataset", {300.0, 0.3, 1.5, true});
  std::string truth_file = (tmp.path() / "dataset" / "truth" / "trajectory.tum").string();
  fs::path result = tmp.path() / "outside";

  /// drift_after_s: from then on the estimate drifts away 0.1 m/s along its x.
  explicit Outside(bool with_scans, double drift_after_s = 1e9) {
    fs::create_directories(result);
    const Pose2 T_estimate_truth = kShift.inverse();
    std::vector<io::TumPose> estimate;
    for (const io::TumPose& p : truth) {
      const double t_s = p.t_s - kOffset_s;
      Pose2 e = T_estimate_truth + Pose2(p.x_m, p.y_m, p.yaw_rad);
      if (t_s > drift_after_s) e = Pose2(e.x() + 0.1 * (t_s - drift_after_s), e.y(), e.yaw());
      estimate.push_back({t_s, e.x(), e.y(), p.z_m, e.yaw()});
    }
    io::write_tum((result / "trajectory.tum").string(), estimate);
    if (with_scans) write_scans();
  }

  void write_scans() const {
    std::string text =
        "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n";
    // The covariance seen in the estimate's frame: J P J^T with J = diag(R(-12 deg), 1).
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    J.topLeftCorner<2, 2>() = kShift.rotation().transpose();
    const Eigen::Matrix3d P = J * kScanVariance.asDiagonal() * J.transpose();
    for (std::size_t k = 50; k < truth.size(); k += 300) {
      const io::TumPose& t = truth[k];
      const Pose2 scan_in_truth(t.x_m + kScanError.x(), t.y_m + kScanError.y(),
                                t.yaw_rad + kScanError.z());
      const Pose2 s = kShift.inverse() + scan_in_truth;
      for (const double v : {t.t_s - kOffset_s, s.x(), s.y(), s.yaw(), P(0, 0), P(0, 1), P(0, 2),
                             P(1, 1), P(1, 2), P(2, 2)}) {
        text += io::format_number(v) + ",";
      }
      text += "100\n";
    }
    testing::write_text((result / "scans.csv").string(), text);
  }

  EvalOptions options(const std::string& align, double t_offset_s = kOffset_s) const {
    EvalOptions o;
    o.result_dir = result.string();
    o.truth_path = truth_file;
    o.name = "outsideSLAM";
    o.t_offset_s = t_offset_s;
    o.align = align;
    return o;
  }
  results::StoredMetrics metrics() const {
    return results::read_metrics_json((result / "metrics.json").string());
  }
};

void expect_shift_recovered(const EstimateAlignment& a) {
  EXPECT_EQ(a.method, "se2");
  EXPECT_EQ(a.t_offset_s, kOffset_s);
  EXPECT_NEAR(a.T_truth_estimate.yaw() * kDegPerRad, 12.0, 1e-6);
  EXPECT_NEAR(a.T_truth_estimate.x(), 30.0, 1e-6);
  EXPECT_NEAR(a.T_truth_estimate.y(), -7.0, 1e-6);
}

TEST(EvalOutside, OffsetAndSe2AlignmentRecoverAKnownShift) {
  const Outside outside(true);
  const EvalOutcome outcome = evaluate(outside.options("se2"));
  const results::StoredMetrics stored = outside.metrics();
  const RunMetrics& m = stored.metrics;
  ASSERT_TRUE(m.eval_scores.has_value());
  // Read back through the file's degrees; the outcome holds the fit itself.
  expect_shift_recovered(m.eval_scores->alignment);
  expect_shift_recovered(outcome.metrics.eval_scores->alignment);
  EXPECT_EQ(m.eval_scores->alignment.positions, outside.truth.size());
  EXPECT_FALSE(m.eval_scores->alignment.window_s.has_value());
  EXPECT_EQ(m.truth, "tum");
  EXPECT_EQ(m.method, "outsideSLAM");
  EXPECT_EQ(m.errors.count, outside.truth.size());
  EXPECT_LT(m.errors.max_m, 1e-6);
  ASSERT_TRUE(m.eval_scores->rpe.has_value());
  const RelativePoseError& rpe = *m.eval_scores->rpe;
  EXPECT_EQ(rpe.delta_m, 10.0);
  EXPECT_GT(rpe.pairs, 2000u);  // 90 m of path: every stamp but those of the last 10 m
  EXPECT_LT(rpe.translation_m.max, 1e-6);
  EXPECT_LT(rpe.rotation_deg.max, 1e-6);
  // The scan covariances turned with the poses: the NEES is the one set in the truth's frame.
  EXPECT_EQ(m.scans, 10);
  EXPECT_EQ(outcome.nees_rows, 10u);
  ASSERT_TRUE(m.anees.has_value());
  EXPECT_NEAR(*m.anees, 6.0, 1e-6);
  for (const results::NeesSample& s :
       results::read_nees_csv((outside.result / "nees.csv").string())) {
    EXPECT_NEAR(s.nees, 6.0, 1e-6);
    EXPECT_GT(s.t_s, kOffset_s);  // on the truth's clock
  }
  // With the offset but no alignment the 30 m shift is all error.
  evaluate(outside.options("none"));
  EXPECT_GT(outside.metrics().metrics.errors.mean_m, 20.0);
  EXPECT_EQ(outside.metrics().metrics.eval_scores->alignment.method, "none");
  // RPE does not see a rigid shift.
  EXPECT_LT(outside.metrics().metrics.eval_scores->rpe->translation_m.max, 1e-6);
}

TEST(EvalOutside, Se2OverTheFirstSecondsOfTheOverlap) {
  // The estimate drifts after 100 s: a fit over the whole overlap is pulled away, a fit over the
  // first 60 s still recovers the shift.
  const Outside outside(false, 100.0);
  evaluate(outside.options("se2:60"));
  const EstimateAlignment first = outside.metrics().metrics.eval_scores->alignment;
  expect_shift_recovered(first);
  ASSERT_TRUE(first.window_s.has_value());
  EXPECT_EQ(*first.window_s, 60.0);
  EXPECT_EQ(first.positions, 601u);  // 10 Hz stamps 0 .. 60 s after the first
  evaluate(outside.options("se2"));
  const EstimateAlignment whole = outside.metrics().metrics.eval_scores->alignment;
  EXPECT_GT(std::abs(whole.T_truth_estimate.x() - 30.0) + std::abs(whole.T_truth_estimate.y() + 7),
            1.0);
}

TEST(EvalOutside, WithoutTheOffsetTheErrorGivesBothSpans) {
  const Outside outside(false);
  for (const double offset_s : {0.0, -kOffset_s}) {
    try {
      evaluate(outside.options("se2", offset_s));
      ADD_FAILURE() << "no InputError";
    } catch (const io::InputError& e) {
      const std::string message = e.what();
      for (const std::string& word :
           {(outside.result / "trajectory.tum").string(), outside.truth_file,
            std::string("estimate 0 .. 300 s"), std::string("truth 1000000000 .. 1000000300 s"),
            std::string("--t-offset S"), std::string("S = 1000000000 ")}) {
        EXPECT_NE(message.find(word), std::string::npos) << message << "\nno '" << word << "'";
      }
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  EXPECT_FALSE(fs::exists(outside.result / "metrics.json"));
}

TEST(EvalOutside, NameAndScanCountsOfAFolderWithoutMetrics) {
  const Outside outside(false);
  evaluate(outside.options("none"));
  results::StoredMetrics stored = outside.metrics();
  EXPECT_EQ(stored.metrics.method, "outsideSLAM");
  EXPECT_EQ(stored.metrics.scans, 0);  // no scans.csv
  EXPECT_FALSE(stored.metrics.anees.has_value());
  EXPECT_FALSE(fs::exists(outside.result / "nees.csv"));
  const std::string text = read_text((outside.result / "metrics.json").string());
  EXPECT_NE(text.find("\"method\": \"outsideSLAM\""), std::string::npos) << text;

  // Scans added, and the record edited by hand ("scans": 0, another name): the count is the rows
  // of scans.csv, the name the record's unless --name says otherwise.
  outside.write_scans();
  std::string edited = text;
  edited.replace(edited.find("outsideSLAM"), 11, "handEdited");
  testing::write_text((outside.result / "metrics.json").string(), edited);
  EvalOptions options = outside.options("se2");
  options.name.clear();
  const EvalOutcome outcome = evaluate(options);
  stored = outside.metrics();
  EXPECT_EQ(stored.metrics.method, "handEdited");
  EXPECT_EQ(stored.metrics.scans, 10);
  EXPECT_EQ(outcome.nees_rows, 10u);
  EXPECT_EQ(results::read_nees_csv((outside.result / "nees.csv").string()).size(), 10u);
}

TEST(EvalOutside, GpsTruthHasNoRpe) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  testing::SyntheticOptions synthetic;
  synthetic.write_truth = false;
  synthetic.duration_s = 120.0;
  testing::write_synthetic_dataset(dataset, synthetic);
  std::vector<io::GpsRecord> gps;
  for (int k = 0; k <= 120; ++k) {
    io::GpsRecord row;
    row.t_log_s = testing::kSyntheticT0_s + k;
    row.latitude_nmea = 4212.225 + 0.0001 * k;  // ~0.19 m north a second
    row.longitude_nmea = 306.2832;
    row.status = 1.0;
    gps.push_back(row);
  }
  io::write_gps_log((dataset / "synth_DGPS.log").string(), gps);
  const fs::path out = tmp.path() / "dr";
  run({dataset.string(), "deadreckoning", out.string(), ""});
  EvalOptions options;
  options.result_dir = out.string();
  const EvalOutcome outcome = evaluate(options);
  EXPECT_EQ(outcome.metrics.truth, "gps");
  ASSERT_TRUE(outcome.metrics.eval_scores.has_value());
  EXPECT_FALSE(outcome.metrics.eval_scores->rpe.has_value());
  const std::string text = read_text((out / "metrics.json").string());
  EXPECT_NE(text.find("\"rpe\": null"), std::string::npos) << text;
}

// The executable: what it prints, and bad values of the new options.
TEST(EvalOutside, CommandLine) {
  const Outside outside(true);
  const std::string dir = testing::shell_quote(outside.result.string());
  const std::string truth = "--truth " + testing::shell_quote(outside.truth_file);
  testing::CliResult r = testing::run_msislab(
      "eval " + dir + " " + truth + " --t-offset 1e9 --align se2:60", outside.tmp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ANEES 6.000 over 10 scans"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("alignment: time offset 1000000000 s, se2 over 601 positions (first 60 s): "
                       "rotation 12.000000 deg, translation (30.000000, -7.000000) m"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("RPE over 10 m, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("translation mean 0.000 m"), std::string::npos) << r.out;
  EXPECT_EQ(outside.metrics().metrics.scans, 10);

  for (const std::string bad :
       {"--align se3", "--align se2:0", "--align se2:-5", "--align se2:x",
        "--align se2:", "--t-offset nan", "--t-offset inf", "--rpe-delta-m 0", "--rpe-delta-m -1",
        "--rpe-delta-m nan", "--name ''", "--t-offset 0"}) {
    r = testing::run_msislab("eval " + dir + " " + truth + " " + bad, outside.tmp);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.out << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
    EXPECT_EQ(r.err.rfind("msislab: ", 0), 0u) << r.err;
    const std::string option = bad.substr(0, bad.find(' '));
    if (bad != "--t-offset 0") {
      EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    }
  }
  // The error without the offset names both files and spans and suggests --t-offset.
  EXPECT_NE(r.err.find("truth 1000000000 .. 1000000300 s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--t-offset S"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace msislab::app
