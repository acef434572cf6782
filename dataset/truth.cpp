#include "dataset/truth.hpp"

#include <algorithm>
#include <filesystem>

#include "io/input_error.hpp"
#include "io/tum.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::dataset {

Truth read_tum_truth(const std::string& path, const std::string& kind) {
  const std::vector<io::TumPose> poses = io::read_tum(path);
  if (poses.empty()) io::fail_file(path, "no poses");
  return tum_truth(poses, kind);
}

Truth tum_truth(const std::vector<io::TumPose>& poses, const std::string& kind) {
  Truth truth;
  truth.kind = kind;
  for (const io::TumPose& p : poses) {
    truth.positions.push_back({p.t_s, {p.x_m, p.y_m}});
    truth.poses.push_back({p.t_s, {Pose2(p.x_m, p.y_m, p.yaw_rad)}});
  }
  truth.depth_m = -poses.front().z_m;
  return truth;
}

Truth load_truth(const DatasetFiles& files, const Calibration& calibration) {
  Truth truth;
  if (files.truth_trajectory) {
    truth = read_tum_truth(*files.truth_trajectory, "simulation");
  } else if (files.gps) {
    truth.kind = "gps";
    truth.positions = load_gps_fixes(files, calibration);
  }
  return truth;
}

StampedPose initial_pose(const Truth& truth, const NavigationLog& navigation,
                         const std::string& dataset_dir, double heading_sigma_rad) {
  if (navigation.heading.empty()) io::fail_file(dataset_dir, "the MRU log has no heading rows");
  const double t_heading0 = navigation.heading.front().t_s;
  StampedPose start;
  // The start is exact by definition (every method starts on the truth); a tiny variance keeps the
  // covariance positive definite.
  start.pose.cov = Eigen::Vector3d(1e-9, 1e-9, heading_sigma_rad * heading_sigma_rad).asDiagonal();
  if (!truth.poses.empty()) {
    start.t_s = truth.positions.front().t_s;
    start.pose.mean = truth.poses.front().pose.mean;
    start.pose.cov(2, 2) = 1e-9;
    return start;
  }
  auto fix = std::find_if(truth.positions.begin(), truth.positions.end(),
                          [&](const PositionFix& f) { return f.t_s >= t_heading0; });
  if (fix == truth.positions.end()) {
    if (!truth.kind.empty()) io::fail_file(dataset_dir, "no GPS fix after the first MRU heading");
    start.t_s = t_heading0;
    start.pose.mean = Pose2(0.0, 0.0, navigation.heading.front().yaw_rad);
    return start;
  }
  start.t_s = fix->t_s;
  start.pose.mean = Pose2(fix->p_world_m.x(), fix->p_world_m.y(),
                          nearest_heading(navigation.heading, fix->t_s).yaw_rad);
  return start;
}

RunInputs load_run_inputs(const std::string& dataset_dir, const std::string& config_path,
                          const std::string& calibration_path) {
  RunInputs in;
  in.dataset = dataset_dir;
  in.files = find_dataset_files(dataset_dir);
  std::optional<NavigationNoise> noise;
  if (in.files.navigation_noise)
    noise = settings::read_navigation_noise(*in.files.navigation_noise);
  settings::DatasetConfig config =
      settings::slam_config_for_dataset(config_path, noise, in.files.navigation_noise.value_or(""));
  in.config = std::move(config.config);
  in.noise_note = std::move(config.noise_note);
  if (!calibration_path.empty()) {
    // A calibration.yaml of the user's (say, the one a run with calibration states wrote) in
    // place of the dataset's own.
    if (!std::filesystem::is_regular_file(calibration_path)) {
      throw io::InputError(calibration_path + ": no such calibration file");
    }
    in.files.calibration = calibration_path;
  }
  in.calibration = load_calibration(in.files);
  in.navigation = load_navigation(in.files, in.calibration);
  in.truth = load_truth(in.files, in.calibration);
  // The config's segments win; without them a simulated dataset's own (its scenario's) apply.
  if (in.config.segments.empty()) in.config.segments = load_truth_segments(in.files);
  in.start = initial_pose(in.truth, in.navigation, dataset_dir,
                          in.config.dead_reckoning.heading_sigma_rad);
  return in;
}

RunInputs run_inputs_of(std::shared_ptr<const DatasetRecords> records, SlamConfig config) {
  RunInputs in;
  in.config = std::move(config);
  in.dataset = records->name;
  in.files.dir = records->name;
  in.calibration = records->calibration;
  in.navigation = navigation_of(records->dvl, records->mti, in.calibration);
  if (!records->truth_trajectory.empty()) {
    in.truth = tum_truth(records->truth_trajectory, "simulation");
  } else if (!records->gps.empty()) {
    in.truth.kind = "gps";
    in.truth.positions = gps_fixes_of(records->gps, in.calibration);
  }
  if (in.config.segments.empty()) in.config.segments = records->truth_segments;
  in.start =
      initial_pose(in.truth, in.navigation, in.dataset, in.config.dead_reckoning.heading_sigma_rad);
  in.records = std::move(records);
  return in;
}

}  // namespace msislab::dataset
