#include "tests/fuzz/reader_targets.hpp"

#include <fstream>
#include <stdexcept>

#include "dataset/dataset.hpp"
#include "io/beam_truth.hpp"
#include "io/detections.hpp"
#include "io/heading_csv.hpp"
#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "io/ply.hpp"
#include "io/sensitivity_csv.hpp"
#include "io/stpere_logs.hpp"
#include "io/tum.hpp"
#include "results/montecarlo_files.hpp"
#include "results/result_readers.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "settings/config_yaml.hpp"
#include "settings/expectations_yaml.hpp"
#include "settings/methods_file.hpp"
#include "settings/scenario_yaml.hpp"
#include "settings/sweep_yaml.hpp"

namespace msislab::fuzz {
namespace {

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

constexpr std::string_view kSweepScenario = R"(seed: 1
scene: {mesh: scene.obj}
vehicle: {depth_m: 2, speed_mps: 0.5, path: [[0, 0], [10, 0]]}
)";

void read_scene_mesh(const std::string& path) {
  io::MeshMaterials materials;
  materials.by_group["walls"] = sim::Material{};
  io::read_mesh(path, materials);
}

/// A sweep file, then each cell's inputs: the overrides applied to the scenario and SLAM config the
/// file names. Beside the fuzzed file lie a valid scenario.yaml and config.yaml for it to name.
void read_sweep_cells(const std::string& path) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  write_file(dir / "scenario.yaml", kSweepScenario);
  write_file(dir / "config.yaml", "trajectory_slam: {iekf_iterations: 3}\n");
  const settings::Sweep sweep = settings::read_sweep(path);
  for (std::size_t i = 0; i < sweep.cells.size(); ++i) settings::cell_inputs(sweep, i);
}

/// A methods file, with the built-in names reserved as `msislab` reserves them, then each
/// method's command with its placeholders filled in.
void read_methods(const std::string& path) {
  const settings::MethodsFile file = settings::read_methods_file(
      path, {"robocentric", "worldcentric", "posegraph", "deadreckoning", "integration"});
  for (const settings::ExternalMethod& method : file.methods) {
    settings::expand_command(method, {"/data", "/out", "/config.yaml", 7});
  }
}

void read_truth_segments(const std::string& path) {
  dataset::DatasetFiles files;
  files.truth_segments = path;
  dataset::load_truth_segments(files);
}

}  // namespace

const std::vector<ReaderTarget>& reader_targets() {
  // The file names are those of a dataset, a result folder and a Monte Carlo directory
  // (docs/formats.md); the mesh and log readers dispatch on them.
  static const std::vector<ReaderTarget> targets = {
      // The St. Pere logs and their simulated twins.
      {"dvl_log", "x_DVL.log", [](const std::string& p) { io::read_dvl_log(p); }},
      {"mti_log", "x_MTi.log", [](const std::string& p) { io::read_mti_log(p); }},
      {"gps_log", "x_DGPS.log", [](const std::string& p) { io::read_gps_log(p); }},
      {"setup_log", "x_SETUP.log", [](const std::string& p) { io::read_setup_log(p); }},
      {"is_log", "x_IS.log", [](const std::string& p) { io::read_is_log(p); }},
      {"beam_times_log", "x_IS_timestamps.log",
       [](const std::string& p) { io::read_beam_times_log(p); }},
      {"detections_csv", "x_detections.csv", [](const std::string& p) { io::read_detections(p); }},
      {"detections_gz", "x_detections.csv.gz",
       [](const std::string& p) { io::read_detections(p); }},
      // A simulated dataset's truth.
      {"tum", "trajectory.tum", [](const std::string& p) { io::read_tum(p); }},
      {"beam_truth_csv", "beams.csv", [](const std::string& p) { io::read_beam_truth(p); }},
      {"segments_csv", "segments.csv", read_truth_segments},
      // YAML: scenario, SLAM config, calibration, sweep, methods file, expectations.
      {"scenario_yaml", "scenario.yaml", [](const std::string& p) { settings::read_scenario(p); }},
      {"slam_config_yaml", "config.yaml",
       [](const std::string& p) { settings::read_slam_config(p); }},
      {"calibration_yaml", "calibration.yaml",
       [](const std::string& p) { settings::read_calibration(p); }},
      {"navigation_noise_yaml", "navigation_noise.yaml",
       [](const std::string& p) { settings::read_navigation_noise(p); }},
      {"sweep_yaml", "sweep.yaml", read_sweep_cells},
      {"methods_yaml", "methods.yaml", read_methods},
      {"expectations_yaml", "expectations.yaml",
       [](const std::string& p) { settings::read_expectations_yaml(p); }},
      // Scene meshes and the map a run writes.
      {"obj_mesh", "scene.obj", read_scene_mesh},
      {"ply_mesh", "scene.ply", read_scene_mesh},
      {"points_ply", "map.ply", [](const std::string& p) { results::read_points_ply(p); }},
      // A result folder.
      {"metrics_json", "metrics.json", [](const std::string& p) { results::read_metrics_json(p); }},
      {"scans_csv", "scans.csv", [](const std::string& p) { results::read_scans_csv(p); }},
      {"errors_csv", "errors.csv", [](const std::string& p) { results::read_errors_csv(p); }},
      {"nees_csv", "nees.csv", [](const std::string& p) { results::read_nees_csv(p); }},
      // A Monte Carlo directory and a sweep.
      {"manifest_json", "montecarlo.json",
       [](const std::string& p) { results::read_manifest_json(p); }},
      {"summary_json", "summary.json", [](const std::string& p) { results::read_summary_json(p); }},
      {"montecarlo_nees_csv", "nees.csv",
       [](const std::string& p) { results::read_montecarlo_nees(p); }},
      {"error_spread_csv", "errors.csv",
       [](const std::string& p) { results::read_error_spread_csv(p); }},
      {"error_histogram_csv", "error_histogram.csv",
       [](const std::string& p) { results::read_error_histogram_csv(p); }},
      {"sweep_csv", "sweep.csv", [](const std::string& p) { results::read_sweep_csv(p); }},
      {"heading_csv", "heading.csv", [](const std::string& p) { io::read_heading_csv(p); }},
      {"sensitivity_csv", "real.csv", [](const std::string& p) { io::read_sensitivity_csv(p); }},
  };
  return targets;
}

const ReaderTarget& reader_target(std::string_view name) {
  std::string names;
  for (const ReaderTarget& target : reader_targets()) {
    if (target.name == name) return target;
    names += (names.empty() ? "" : ", ") + target.name;
  }
  throw std::invalid_argument("no reader target '" + std::string(name) + "' (targets: " + names +
                              ")");
}

Outcome read_bytes(const ReaderTarget& target, std::string_view bytes,
                   const std::filesystem::path& dir) {
  // A folder per target: some readers find companion files beside theirs.
  const std::filesystem::path target_dir = dir / target.name;
  std::filesystem::create_directories(target_dir);
  const std::string path = (target_dir / target.file_name).string();
  write_file(path, bytes);
  try {
    target.read(path);
  } catch (const io::InputError&) {
    return Outcome::kRejected;
  }
  return Outcome::kAccepted;
}

}  // namespace msislab::fuzz
