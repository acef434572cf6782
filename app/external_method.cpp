#include "app/external_method.hpp"

#include <cmath>
#include <filesystem>

#include "app/external_program.hpp"
#include "app/method_result.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "results/results.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// Why the program gave no result, from how it ended; empty when it exited with status 0.
std::string ending_problem(const ProgramOutcome& outcome, double time_limit_s) {
  if (!outcome.process.start_error.empty()) return outcome.process.start_error;
  if (outcome.timed_out) {
    return "time limit of " + io::format_number(time_limit_s) +
           " s exceeded: its process group was stopped (SIGTERM, then SIGKILL)";
  }
  if (outcome.process.ok()) return "";
  return describe_failure(outcome.process, "");
}

/// A file the program wrote in {out}: a regular file there, never a link (the program must not
/// make msislab read from elsewhere). False when it is absent.
bool program_file(const fs::path& out, const char* name, fs::path& path) {
  path = out / name;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (ec || status.type() == fs::file_type::not_found) return false;
  if (status.type() != fs::file_type::regular) {
    throw io::InputError(path.string() + ": not a regular file (a link or folder is not read)");
  }
  return true;
}

std::vector<StampedPose> read_trajectory(const fs::path& out) {
  fs::path path;
  if (!program_file(out, "trajectory.tum", path)) {
    throw io::InputError("it wrote no trajectory.tum in {out}");
  }
  std::vector<StampedPose> trajectory;
  for (const io::TumPose& p : io::read_tum(path.string())) {
    trajectory.push_back({p.t_s, {Pose2(p.x_m, p.y_m, p.yaw_rad)}});
  }
  if (trajectory.size() < 2) {
    io::fail_file(path.string(), "fewer than 2 poses (" + std::to_string(trajectory.size()) + ")");
  }
  return trajectory;
}

/// scans.csv as msislab writes it (pose and covariance per scan; no points).
std::optional<std::vector<PlacedScan>> read_scans(const fs::path& out) {
  fs::path path;
  if (!program_file(out, "scans.csv", path)) return std::nullopt;
  std::vector<PlacedScan> scans;
  for (const StampedPose& pose : results::read_scans_csv(path.string())) {
    PlacedScan scan;
    scan.scan.t_s = pose.t_s;
    scan.centre_world = pose;
    scans.push_back(scan);
  }
  return scans;
}

/// Scores the estimate against the dataset's truth as run_method scores a built-in method's.
void score(const Method& method, const dataset::RunInputs& in, double runtime_s,
           MethodResult& result) {
  const dataset::Truth& truth = in.truth;
  result.errors = position_errors(result.trajectory, truth.positions);
  result.metrics = score_errors(truth, result.errors, in.config.segments, "trajectory.tum");
  result.t_first_truth_s = truth.positions.front().t_s;
  RunMetrics& metrics = *result.metrics;
  metrics.method = method.name;
  metrics.runtime_s = runtime_s;
  if (!result.scans) return;
  metrics.scans = static_cast<int>(result.scans->size());
  std::vector<StampedPose> poses;
  for (const PlacedScan& s : *result.scans) poses.push_back(s.centre_world);
  result.nees = scan_nees(poses, truth);
  for (std::size_t k = 0; k < result.nees.size(); ++k) {
    if (!std::isfinite(result.nees[k].nees)) {
      throw io::InputError("scans.csv: the covariance of scan " + std::to_string(k) +
                           " is not positive definite (its NEES is not finite)");
    }
  }
  metrics.anees = average_nees(result.nees);
}

}  // namespace

MethodResult run_external_method(const Method& method, const dataset::RunInputs& in,
                                 const ExternalSetup& setup) {
  const settings::ExternalMethod& spec = *method.external;
  const fs::path work(io::absolute_path(setup.work_dir));  // {out} is absolute (docs/cli.md)
  std::error_code ec;
  fs::remove_all(work, ec);
  const fs::path out = work / "out";
  fs::create_directories(out, ec);
  if (ec) throw ExternalMethodError("cannot make " + out.string() + ": " + ec.message(), {});
  const settings::PlaceholderValues values{io::absolute_path(setup.dataset_dir), out.string(),
                                           io::absolute_path(setup.config_path), setup.seed};
  ProgramSpec program;
  program.argv = settings::expand_command(spec, values);
  program.environment = spec.environment;
  program.working_dir = out.string();
  program.stderr_path = (work / "stderr.log").string();
  program.time_limit_s = spec.time_limit_s;
  const ProgramOutcome outcome = run_program(program);
  std::vector<std::string> tail = io::last_lines(program.stderr_path, kStderrTailLines);
  const std::string problem = ending_problem(outcome, spec.time_limit_s);
  if (!problem.empty()) throw ExternalMethodError(problem, std::move(tail));
  MethodResult result;
  try {
    // Only {out}/trajectory.tum and {out}/scans.csv are read; {out} must still be msislab's folder.
    if (fs::symlink_status(out, ec).type() != fs::file_type::directory) {
      throw io::InputError("{out} was replaced (it is no longer the folder msislab made)");
    }
    result.method = method.name;
    result.trajectory = read_trajectory(out);
    result.scans = read_scans(out);
    result.depth_m = in.truth.depth_m;
    if (!in.truth.kind.empty()) score(method, in, outcome.wall_s, result);
  } catch (const io::InputError& e) {
    throw ExternalMethodError(e.what(), std::move(tail));
  }
  return result;
}

}  // namespace msislab::app
