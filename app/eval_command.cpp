#include "app/eval_command.hpp"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "app/cli.hpp"
#include "app/method_result.hpp"
#include "dataset/dataset.hpp"
#include "eval/alignment.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// eval adds its scores to the folder: a result that msislab wrote, or a folder of the user's with
/// a trajectory.tum, where the score files are msislab's only when it wrote them before (its marker
/// of kind "scores"); a score file of the user's is never replaced.
void check_scores_folder(const std::string& dir) {
  const std::string kind = io::output_kind(dir);
  if (kind == "result" || kind == "scores") return;
  for (const char* name : {"metrics.json", "nees.csv"}) {
    const fs::path file = fs::path(dir) / name;
    if (fs::exists(file)) {
      io::fail_file(file.string(),
                    "is a file that msislab did not write; eval writes its scores "
                    "there, so move it away");
    }
  }
  io::write_output_marker(dir, "scores", "eval", nullptr);
}

/// Lists eval's files in a result folder's marker, so that run replaces the folder later.
void record_scores(const std::string& dir) {
  std::vector<std::string> names = {"metrics.json"};
  if (fs::exists(fs::path(dir) / "nees.csv")) names.push_back("nees.csv");
  io::record_output_entries(dir, names);
}

/// The run's own record. A result written without truth has none: then only --truth can score it,
/// and the run's figures are unknown.
results::StoredMetrics read_run_record(const EvalOptions& options, const fs::path& dir) {
  const std::string path = (dir / "metrics.json").string();
  if (fs::exists(path)) return results::read_metrics_json(path);
  if (options.truth_path.empty()) {
    io::fail_file(path, "missing (a result written without truth needs --truth FILE)");
  }
  results::StoredMetrics stored;
  stored.metrics.method = "unknown";
  stored.metrics.runtime_s = std::numeric_limits<double>::quiet_NaN();
  return stored;
}

/// The truth, and the file it came from for messages.
struct TruthSource {
  dataset::Truth truth;
  std::string file;
};

TruthSource dataset_truth(const results::StoredMetrics& stored, const std::string& metrics_path) {
  if (stored.dataset_dir.empty() || !fs::is_directory(stored.dataset_dir)) {
    io::fail_file(metrics_path, "key 'dataset': the dataset '" + stored.dataset_dir +
                                    "' is not there any more; give --truth FILE");
  }
  const dataset::DatasetFiles files = dataset::find_dataset_files(stored.dataset_dir);
  dataset::Truth truth = dataset::load_truth(files, dataset::load_calibration(files));
  if (truth.kind.empty()) {
    io::fail_file(stored.dataset_dir,
                  "the dataset has no truth (truth/trajectory.tum or "
                  "*_DGPS.log); give --truth FILE");
  }
  return {std::move(truth), files.truth_trajectory ? *files.truth_trajectory : *files.gps};
}

/// The shortest text that reads back as the same double, without an exponent: log times of 1e9 s
/// read as such.
std::string plain_number(double value) {
  char text[400];
  const auto [end, ec] = std::to_chars(text, text + sizeof(text), value, std::chars_format::fixed);
  return ec == std::errc() ? std::string(text, end) : io::format_number(value);
}

std::string span_text(double first_s, double last_s) {
  return plain_number(first_s) + " .. " + plain_number(last_s) + " s";
}

/// Fails naming both files and both time spans when no truth stamp falls inside the estimate's
/// span [t0_s, t1_s] (as in its file) once shifted by t_offset_s.
void require_overlap(const std::vector<StampedPose>& trajectory, const TruthSource& truth,
                     const std::string& estimate_file, double t0_s, double t1_s,
                     double t_offset_s) {
  if (!matched_positions(trajectory, truth.truth.positions).empty()) return;
  const double truth0_s = truth.truth.positions.front().t_s;
  std::string spans = "estimate " + span_text(t0_s, t1_s);
  if (t_offset_s != 0.0) {
    spans += " (with --t-offset " + plain_number(t_offset_s) + ": " +
             span_text(trajectory.front().t_s, trajectory.back().t_s) + ")";
  }
  io::fail_file(estimate_file + " and " + truth.file,
                "the time spans do not overlap (no truth stamp inside the estimate's span): " +
                    spans + ", truth " + span_text(truth0_s, truth.truth.positions.back().t_s) +
                    "; shift the estimate with --t-offset S (t_truth = t_estimate + S; S = " +
                    plain_number(truth0_s - t0_s) + " lines up the first stamps)");
}

/// Fits the alignment the options ask for and applies it to the trajectory and the scan poses.
EstimateAlignment align_estimate(const EvalOptions& options, const TruthSource& truth,
                                 const std::string& estimate_file,
                                 std::vector<StampedPose>& trajectory,
                                 std::optional<std::vector<StampedPose>>& scans) {
  const AlignOption align = parse_align_option(options.align);
  EstimateAlignment alignment;
  alignment.t_offset_s = options.t_offset_s;
  if (!align.se2) return alignment;
  alignment.method = "se2";
  alignment.window_s = align.window_s;
  try {
    const Se2Fit fit = fit_se2(trajectory, truth.truth.positions, align.window_s);
    alignment.T_truth_estimate = fit.T_truth_estimate;
    alignment.positions = fit.positions;
  } catch (const std::invalid_argument& e) {
    io::fail_file(estimate_file + " and " + truth.file,
                  "--align " + options.align + ": " + e.what());
  }
  trajectory = transform_poses(alignment.T_truth_estimate, trajectory);
  if (scans) scans = transform_poses(alignment.T_truth_estimate, *scans);
  return alignment;
}

void check_options(const EvalOptions& options) {
  parse_align_option(options.align);
  if (!std::isfinite(options.t_offset_s)) {
    throw io::InputError("--t-offset " + io::format_number(options.t_offset_s) +
                         ": expected a finite number of seconds");
  }
  if (!(options.rpe_delta_m > 0.0) || !std::isfinite(options.rpe_delta_m)) {
    throw io::InputError("--rpe-delta-m " + io::format_number(options.rpe_delta_m) +
                         ": expected a distance in metres > 0");
  }
}

}  // namespace

AlignOption parse_align_option(const std::string& text) {
  if (text == "none") return {};
  if (text == "se2") return {true, std::nullopt};
  const std::string prefix = "se2:";
  if (text.rfind(prefix, 0) == 0) {
    const char* begin = text.data() + prefix.size();
    const char* end = text.data() + text.size();
    double window_s = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, end, window_s);
    if (ec == std::errc() && ptr == end && std::isfinite(window_s) && window_s > 0.0) {
      return {true, window_s};
    }
  }
  throw io::InputError("--align '" + text + "': expected none, se2 or se2:N (N seconds > 0)");
}

EvalOutcome evaluate(const EvalOptions& options) {
  check_options(options);
  const fs::path dir(options.result_dir);
  if (!fs::is_directory(dir)) io::fail_file(options.result_dir, "no such result directory");
  const results::StoredMetrics stored = read_run_record(options, dir);
  const std::vector<TimeSegment> segments =
      options.config_path.empty() ? stored.metrics.segment_windows
                                  : settings::read_slam_config(options.config_path).segments;
  const std::string estimate_file = (dir / "trajectory.tum").string();
  const std::vector<io::TumPose> tum = io::read_tum(estimate_file);
  std::vector<StampedPose> trajectory;
  for (const io::TumPose& p : tum) {
    trajectory.push_back({p.t_s + options.t_offset_s, {Pose2(p.x_m, p.y_m, p.yaw_rad)}});
  }
  const fs::path scans_path = dir / "scans.csv";
  std::optional<std::vector<StampedPose>> scans;
  if (fs::exists(scans_path)) {
    scans = shift_times(results::read_scans_csv(scans_path.string()), options.t_offset_s);
  }
  const TruthSource truth =
      options.truth_path.empty()
          ? dataset_truth(stored, (dir / "metrics.json").string())
          : TruthSource{dataset::read_tum_truth(options.truth_path, "tum"), options.truth_path};
  require_overlap(trajectory, truth, estimate_file, tum.front().t_s, tum.back().t_s,
                  options.t_offset_s);
  EvalScores scores;
  scores.alignment = align_estimate(options, truth, estimate_file, trajectory, scans);
  if (!truth.truth.poses.empty()) {
    scores.rpe = relative_pose_error(trajectory, truth.truth.poses, options.rpe_delta_m);
  }

  EvalOutcome outcome;
  RunMetrics& metrics = outcome.metrics;
  metrics = score_trajectory(truth.truth, trajectory, segments, truth.file);
  metrics.method = options.name.empty() ? stored.metrics.method : options.name;
  // The scans scored are the rows of scans.csv; without it the run's own count stands.
  metrics.scans = scans ? static_cast<int>(scans->size()) : stored.metrics.scans;
  metrics.matches_accepted = stored.metrics.matches_accepted;
  metrics.runtime_s = stored.metrics.runtime_s;
  metrics.diagnostics = stored.metrics.diagnostics;
  metrics.eval_scores = scores;
  std::vector<results::NeesSample> nees;
  if (scans) nees = scan_nees(*scans, truth.truth);
  metrics.anees = average_nees(nees);
  outcome.nees_rows = nees.size();
  check_scores_folder(options.result_dir);
  write_scores(options.result_dir, metrics, nees, stored.dataset_dir,
               options.truth_path.empty() ? "" : io::absolute_path(options.truth_path));
  record_scores(options.result_dir);
  return outcome;
}

namespace {

void print_outcome(const EvalOptions& options, const EvalOutcome& outcome) {
  const RunMetrics& m = outcome.metrics;
  std::cout << std::fixed << std::setprecision(3) << "wrote " << options.result_dir
            << "/metrics.json: mean error " << m.errors.mean_m << " m against " << m.truth;
  if (m.anees) {
    std::cout << ", ANEES " << *m.anees << " over " << outcome.nees_rows << " scans (nees.csv)";
  }
  std::cout << "\n";
  const EstimateAlignment& a = m.eval_scores->alignment;
  if (a.method != "none" || a.t_offset_s != 0.0) {
    std::cout << "alignment: time offset " << plain_number(a.t_offset_s) << " s";
    if (a.method != "none") {
      std::cout << ", " << a.method << " over " << a.positions << " positions";
      if (a.window_s) std::cout << " (first " << plain_number(*a.window_s) << " s)";
      std::cout << ": rotation " << std::setprecision(6) << a.T_truth_estimate.yaw() * 180.0 / M_PI
                << " deg, translation (" << a.T_truth_estimate.x() << ", " << a.T_truth_estimate.y()
                << ") m" << std::setprecision(3);
    }
    std::cout << "\n";
  }
  const std::optional<RelativePoseError>& rpe = m.eval_scores->rpe;
  if (!rpe) {
    std::cout << "RPE: unavailable (the " << m.truth << " truth has positions only, no heading)\n";
  } else if (rpe->pairs == 0) {
    std::cout << "RPE over " << plain_number(rpe->delta_m)
              << " m: no pair (the truth travels less inside the estimate's span)\n";
  } else {
    const SampleSummary& t = rpe->translation_m;
    const SampleSummary& r = rpe->rotation_deg;
    std::cout << "RPE over " << plain_number(rpe->delta_m) << " m, " << rpe->pairs
              << " pairs: translation mean " << t.mean << " m, RMSE " << t.rmse << " m, median "
              << t.median << " m, max " << t.max << " m; rotation mean " << r.mean << " deg, RMSE "
              << r.rmse << " deg, median " << r.median << " deg, max " << r.max << " deg\n";
  }
  std::cout.flush();
}

}  // namespace

void add_eval_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* eval = app.add_subcommand(
      "eval",
      "Score a result directory (of `msislab run`, or a trajectory.tum from elsewhere) against "
      "truth; rewrites metrics.json and nees.csv");
  eval->add_option("RESULT_DIR", options->result_dir,
                   "Result directory (trajectory.tum; metrics.json and scans.csv when present)")
      ->required();
  eval->add_option("--truth,-t", options->truth_path,
                   "TUM truth file (default: the truth of the dataset recorded in metrics.json)");
  eval->add_option("--config,-c", options->config_path,
                   "SLAM config YAML whose segments replace the recorded segment windows");
  eval->add_option("--name", options->name,
                   "Method name recorded in metrics.json (shown by plot and report); default: "
                   "the recorded one, else 'unknown'")
      ->type_name("NAME")
      ->check(CLI::Validator(
          [](std::string& name) { return name.empty() ? std::string("empty name") : ""; }, ""));
  eval->add_option("--t-offset", options->t_offset_s,
                   "Seconds added to the estimate's time stamps before scoring: t_truth = "
                   "t_estimate + S (default 0)")
      ->type_name("S");
  eval->add_option("--align", options->align,
                   "none (default), se2 (rigid 2-D fit of the estimate's positions onto the "
                   "truth's over the whole overlap) or se2:N (over its first N seconds)")
      ->type_name("none|se2|se2:N");
  eval->add_option("--rpe-delta-m", options->rpe_delta_m,
                   "Truth path length in metres between the two poses of each relative pose "
                   "error pair (default 10)")
      ->type_name("D");
  eval->callback([options] { print_outcome(*options, evaluate(*options)); });
}

}  // namespace msislab::app
