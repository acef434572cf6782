// `msislab simulate` end to end on a small box basin: every dataset file read back by the io
// readers at the St. Pere rates, beam truth against the box's geometry and the rendered echoes,
// byte-for-byte determinism (same seed, any thread count), dead reckoning on the result, bad input
// rejected with nothing written, and the command line's exit codes (docs/simulator.md).
#include "app/simulate_command.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_command.hpp"
#include "cli_runner.hpp"
#include "dataset/dataset.hpp"
#include "dataset/sonar_readings.hpp"
#include "io/detections.hpp"
#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "io/stpere_logs.hpp"
#include "io/tum.hpp"
#include "settings/config_yaml.hpp"
#include "settings/scenario_yaml.hpp"
#include "sim/detection_model.hpp"
#include "stats/sample_statistics.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

constexpr double kPi = 3.14159265358979323846;

// The basin: x in [-20, 20], y in [-10, 10], walls from z = +1 down to the bottom at z = -3.3.
constexpr double kHalfLength_m = 20.0;
constexpr double kHalfWidth_m = 10.0;
constexpr double kBottomZ_m = -3.3;

// A loop 10 + 8 + 10 + 7 = 35 m long at 0.5 m/s (about 65 s), at least 5 m from every wall, whose
// last leg is long enough after the final corner for the vehicle to reach its end.
constexpr double kPathLength_m = 35.0;
constexpr double kSpeed_mps = 0.5;
constexpr double kStartTime_s = 1093455407.0;  // the default vehicle.start_time_s
constexpr const char* kBoxScenarioYaml =
    "name: box\n"
    "seed: 11\n"
    "scene:\n"
    "  mesh: box.obj\n"
    "  groups:\n"
    "    walls: {backscatter: 0.8, specular: 0.2}\n"
    "    bottom: {backscatter: 0.3, specular: 0.5}\n"
    "vehicle:\n"
    "  depth_m: 1.5\n"
    "  speed_mps: 0.5\n"
    "  path: [[-5, -4], [5, -4], [5, 4], [-5, 4], [-5, -3]]\n"
    "segments: {first_half: [0, 30], second_half: [30, 65]}\n";

const char* const kDatasetFiles[] = {
    "box_IS.log",    "box_IS_timestamps.log", "box_detections.csv.gz", "box_SETUP.log",
    "box_DVL.log",   "box_MTi.log",           "box_DGPS.log",          "calibration.yaml",
    "scenario.yaml", "truth/trajectory.tum",  "truth/beams.csv",       "truth/segments.csv"};

// The box: 4 walls (2 triangles each, group `walls`) and the bottom (2 triangles, group `bottom`),
// counter-clockwise seen from inside so every normal faces the water.
sim::TriangleMesh box_basin() {
  sim::TriangleMesh mesh;
  const float x = static_cast<float>(kHalfLength_m), y = static_cast<float>(kHalfWidth_m);
  const float bottom = static_cast<float>(kBottomZ_m), top = 1.0f;
  const float corners[4][2] = {{-x, -y}, {x, -y}, {x, y}, {-x, y}};
  for (const float z : {bottom, top}) {
    for (const auto& c : corners) mesh.vertices_m.emplace_back(c[0], c[1], z);
  }
  mesh.materials = {{"walls", 0.8f, 0.2f}, {"bottom", 0.3f, 0.5f}};
  mesh.group_names = {"walls", "bottom"};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;  // bottom corners i, j; top corners i + 4, j + 4
    mesh.triangles.emplace_back(i, i + 4, j + 4);
    mesh.triangles.emplace_back(i, j + 4, j);
    mesh.material_ids.insert(mesh.material_ids.end(), 2, 0u);
  }
  mesh.triangles.emplace_back(0, 1, 2);
  mesh.triangles.emplace_back(0, 2, 3);
  mesh.material_ids.insert(mesh.material_ids.end(), 2, 1u);
  return mesh;
}

// Writes box.obj and scenario.yaml (kBoxScenarioYaml + extra) into dir; returns the scenario's
// path.
std::string write_box_scenario(const fs::path& dir, const std::string& extra = "") {
  fs::create_directories(dir);
  io::write_obj((dir / "box.obj").string(), box_basin());
  return write_text((dir / "scenario.yaml").string(), std::string(kBoxScenarioYaml) + extra);
}

SimulateOptions options_for(const std::string& scenario, const fs::path& out, int threads = 2) {
  SimulateOptions options;
  options.scenario_path = scenario;
  options.out_dir = out.string();
  options.threads = threads;
  return options;
}

// One simulation of the box, shared by the tests that only read it.
struct BoxDataset {
  TempDir tmp;
  std::string scenario;
  fs::path dir;
  SimulateSummary summary;
  BoxDataset() : scenario(write_box_scenario(tmp.path())), dir(tmp.path() / "dataset") {
    summary = simulate(options_for(scenario, dir));
  }
};
const BoxDataset& box_dataset() {
  static const BoxDataset dataset;
  return dataset;
}

// Every file under dir, relative path -> bytes.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) {
      files[fs::relative(entry.path(), dir).string()] = read_text(entry.path().string());
    }
  }
  return files;
}

void expect_same_files(const fs::path& a, const fs::path& b) {
  const auto files_a = files_of(a), files_b = files_of(b);
  std::vector<std::string> names_a, names_b;
  for (const auto& [name, bytes] : files_a) names_a.push_back(name);
  for (const auto& [name, bytes] : files_b) names_b.push_back(name);
  ASSERT_EQ(names_a, names_b);
  for (const auto& [name, bytes] : files_a) {
    EXPECT_TRUE(bytes == files_b.at(name)) << name << " differs between " << a << " and " << b;
  }
}

// Samples per second over a stream's span.
template <typename Row>
double rate_hz(const std::vector<Row>& rows) {
  if (rows.size() < 2) return 0.0;
  return static_cast<double>(rows.size() - 1) / (rows.back().t_log_s - rows.front().t_log_s);
}

double wrap_angle(double a_rad) { return std::remainder(a_rad, 2.0 * kPi); }

// One row of truth/beams.csv.
struct BeamRow {
  double t_s = 0.0, x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, bearing_rad = 0.0;
  std::optional<double> first_hit_range_m, strongest_range_m;
  bool multipath = false;
  std::string surface;                       ///< strongest_surface
  std::optional<double> bearing_offset_rad;  ///< strongest_bearing_offset_rad
};

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, separator)) fields.push_back(field);
  if (!line.empty() && line.back() == separator) fields.emplace_back();
  return fields;
}

constexpr const char* kBeamsHeader =
    "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
    "strongest_surface,strongest_bearing_offset_rad";

std::vector<BeamRow> read_beams_csv(const std::string& path) {
  std::stringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, kBeamsHeader);
  std::vector<BeamRow> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line, ',');
    if (f.size() != 10) {
      ADD_FAILURE() << path << ": expected 10 columns: " << line;
      continue;
    }
    auto optional = [](const std::string& text) -> std::optional<double> {
      if (text.empty()) return std::nullopt;
      return std::stod(text);
    };
    EXPECT_TRUE(f[7] == "0" || f[7] == "1") << line;
    rows.push_back({std::stod(f[0]), std::stod(f[1]), std::stod(f[2]), std::stod(f[3]),
                    std::stod(f[4]), optional(f[5]), optional(f[6]), f[7] == "1", f[8],
                    optional(f[9])});
  }
  return rows;
}

// Range from the sonar head along a horizontal beam to the first wall of the box.
double range_to_wall_m(const BeamRow& beam, const SonarMount& mount) {
  const double c = std::cos(beam.yaw_rad), s = std::sin(beam.yaw_rad);
  const double hx = beam.x_m + c * mount.x_m - s * mount.y_m;
  const double hy = beam.y_m + s * mount.x_m + c * mount.y_m;
  const double dx = std::cos(beam.yaw_rad + beam.bearing_rad);
  const double dy = std::sin(beam.yaw_rad + beam.bearing_rad);
  double range_m = 1e300;
  if (std::abs(dx) > 1e-12)
    range_m = std::min(range_m, ((dx > 0 ? 1 : -1) * kHalfLength_m - hx) / dx);
  if (std::abs(dy) > 1e-12)
    range_m = std::min(range_m, ((dy > 0 ? 1 : -1) * kHalfWidth_m - hy) / dy);
  return range_m;
}

TEST(SimulateCommand, WritesEveryFileAndTheReadersReadThemBack) {
  const BoxDataset& box = box_dataset();
  for (const char* name : kDatasetFiles) {
    EXPECT_TRUE(fs::is_regular_file(box.dir / name)) << name;
  }
  // Nothing else is left next to the dataset (no temporary or partial folders).
  std::vector<std::string> siblings;
  for (const auto& entry : fs::directory_iterator(box.tmp.path())) {
    siblings.push_back(entry.path().filename().string());
  }
  std::sort(siblings.begin(), siblings.end());
  EXPECT_EQ(siblings, (std::vector<std::string>{"box.obj", "dataset", "scenario.yaml"}));

  const dataset::DatasetFiles files = dataset::find_dataset_files(box.dir.string());
  EXPECT_TRUE(files.is_log && files.setup && files.dvl && files.mti && files.gps &&
              files.calibration && files.truth_trajectory && files.truth_beams);

  const double duration_s = box.summary.duration_s;
  std::printf("simulated %.1f s: %zu beams, %zu DVL samples, render %.3f s, total %.3f s\n",
              duration_s, box.summary.beams, box.summary.dvl_samples, box.summary.render_s,
              box.summary.total_s);
  // At constant speed the loop takes its length over the speed, a little less for cut corners.
  EXPECT_GT(duration_s, 0.85 * kPathLength_m / kSpeed_mps);
  EXPECT_LT(duration_s, 1.1 * kPathLength_m / kSpeed_mps);
  EXPECT_EQ(box.summary.rays_per_beam, 16u * 12u);

  // Sonar: one row per beam, 500 bins, the angle stepping down one 1.8 deg step per beam, 200
  // beams per 13.8 s revolution.
  const auto beams = io::read_is_log((box.dir / "box_IS.log").string());
  ASSERT_EQ(beams.size(), box.summary.beams);
  ASSERT_GT(beams.size(), 200u);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    ASSERT_EQ(beams[i].intensity.size(), 500u) << "beam " << i;
    if (i == 0) continue;
    ASSERT_NEAR(wrap_angle(beams[i].transducer_angle_rad - beams[i - 1].transducer_angle_rad),
                -2.0 * kPi / 200.0, 1e-9)
        << "beam " << i;
  }
  // The log's times run the mount's clock offset (St. Pere's, 0.66 s) behind the navigation
  // clock; calibration.yaml carries it (checked below).
  const double offset_s =
      sim::calibration_of(settings::read_scenario(box.scenario)).sonar.time_offset_s;
  EXPECT_EQ(offset_s, 0.66);
  EXPECT_NEAR(beams.front().t_log_s, kStartTime_s - offset_s, 1e-9);
  EXPECT_NEAR(rate_hz(beams) * 13.8, 200.0, 1.0);
  const auto in_first_revolution = std::count_if(beams.begin(), beams.end(), [&](const auto& b) {
    return b.t_log_s < beams.front().t_log_s + 13.8 - 1e-6;
  });
  EXPECT_NEAR(static_cast<double>(in_first_revolution), 200.0, 1.0);

  const io::SonarSetup setup = io::read_setup_log((box.dir / "box_SETUP.log").string());
  EXPECT_NEAR(setup.range_m, 50.0, 1e-9);
  EXPECT_NEAR(setup.bin_m, 0.1, 1e-12);
  EXPECT_NEAR(setup.step_rad, 2.0 * kPi / 200.0, 1e-12);

  const auto dvl = io::read_dvl_log((box.dir / "box_DVL.log").string());
  EXPECT_EQ(dvl.size(), box.summary.dvl_samples);
  EXPECT_NEAR(rate_hz(dvl), 1.5, 0.1);
  const auto mti = io::read_mti_log((box.dir / "box_MTi.log").string());
  EXPECT_NEAR(rate_hz(mti), 10.0, 0.1);
  EXPECT_NEAR(static_cast<double>(mti.size()), 10.0 * duration_s, 2.0);
  const auto gps = io::read_gps_log((box.dir / "box_DGPS.log").string());
  EXPECT_NEAR(rate_hz(gps), 1.0, 0.05);
  EXPECT_NEAR(static_cast<double>(gps.size()), duration_s, 2.0);

  // Truth trajectory: at least 10 Hz over the whole run, at the scenario's depth.
  const auto truth = io::read_tum((box.dir / "truth" / "trajectory.tum").string());
  ASSERT_GE(truth.size(), 2u);
  EXPECT_EQ(truth.front().t_s, kStartTime_s);
  EXPECT_NEAR(truth.back().t_s - truth.front().t_s, duration_s, 0.1);
  double max_gap_s = 0.0;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    max_gap_s = std::max(max_gap_s, truth[i].t_s - truth[i - 1].t_s);
  }
  EXPECT_LE(max_gap_s, 0.1 + 1e-6);
  EXPECT_GE(static_cast<double>(truth.size()), 10.0 * duration_s);
  EXPECT_EQ(truth.front().z_m, -1.5);
  EXPECT_NEAR(truth.front().x_m, -5.0, 1e-9);
  EXPECT_NEAR(truth.front().y_m, -4.0, 1e-9);
  EXPECT_NEAR(truth.front().yaw_rad, 0.0, 1e-9);

  // calibration.yaml is the scenario's mounts and frame.
  const Calibration expected = sim::calibration_of(settings::read_scenario(box.scenario));
  const Calibration c = settings::read_calibration((box.dir / "calibration.yaml").string());
  EXPECT_EQ(c.mru.yaw_offset_deg, expected.mru.yaw_offset_deg);
  EXPECT_EQ(c.dvl.yaw_deg, expected.dvl.yaw_deg);
  EXPECT_EQ(c.dvl.x_m, expected.dvl.x_m);
  EXPECT_EQ(c.dvl.y_m, expected.dvl.y_m);
  EXPECT_EQ(c.sonar.x_m, expected.sonar.x_m);
  EXPECT_EQ(c.sonar.y_m, expected.sonar.y_m);
  EXPECT_EQ(c.sonar.z_m, expected.sonar.z_m);
  EXPECT_NEAR(c.sonar.bearing_offset_rad, expected.sonar.bearing_offset_rad, 1e-12);
  EXPECT_EQ(c.sonar.bearing_sign, expected.sonar.bearing_sign);
  EXPECT_EQ(c.sonar.time_offset_s, expected.sonar.time_offset_s);
  EXPECT_EQ(c.frame.origin_latitude_deg, expected.frame.origin_latitude_deg);
  EXPECT_EQ(c.frame.origin_longitude_deg, expected.frame.origin_longitude_deg);

  EXPECT_EQ(read_text((box.dir / "scenario.yaml").string()), kBoxScenarioYaml);

  // beams.csv: one row per beam, at the beams' times on the navigation clock.
  const std::vector<BeamRow> rows = read_beams_csv((box.dir / "truth" / "beams.csv").string());
  ASSERT_EQ(rows.size(), beams.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_NEAR(rows[i].t_s, beams[i].t_log_s + c.sonar.time_offset_s, 1e-6) << "beam " << i;
  }
}

TEST(SimulateCommand, BeamTruthAgreesWithTheGeometryAndTheEchoes) {
  const BoxDataset& box = box_dataset();
  const std::vector<BeamRow> rows = read_beams_csv((box.dir / "truth" / "beams.csv").string());
  const SonarMount mount =
      settings::read_calibration((box.dir / "calibration.yaml").string()).sonar;
  ASSERT_FALSE(rows.empty());
  std::size_t with_hit = 0, close = 0, multipath = 0, bottom_strongest = 0, agree = 0;
  double max_geometry_error_m = 0.0;
  for (const BeamRow& row : rows) {
    if (!row.first_hit_range_m) continue;
    ++with_hit;
    // The axis is horizontal (tilt 0) at 1.5 m depth: its first surface is a wall of the box.
    max_geometry_error_m = std::max(max_geometry_error_m,
                                    std::abs(*row.first_hit_range_m - range_to_wall_m(row, mount)));
    // Each ray is a surface patch whose echo spreads over the patch's ranges and the receiver's
    // 0.9 m tail, and the walls' roughness (10 dB) makes bright and dark patches, so the
    // strongest bin lies among the ranges the beam's rays (+-2 beamwidths, +-6 deg) cover on the
    // walls, not at the axis's first hit: on an oblique wall, or where a bright patch of a
    // nearer wall at the beam's edge outshines a dark one on the axis, it can be metres away
    // (docs/simulator.md). Before the footprints and the roughness, echoes were points on even
    // walls, and 0.3 m from the first hit held for 90 % of this box's beams; now for 70 %.
    double lobe_min_m = 1e300, lobe_max_m = 0.0;
    for (double da_deg = -6.0; da_deg <= 6.0 + 1e-9; da_deg += 0.1) {
      BeamRow turned = row;
      turned.bearing_rad += da_deg * kPi / 180.0;
      lobe_min_m = std::min(lobe_min_m, range_to_wall_m(turned, mount));
      lobe_max_m = std::max(lobe_max_m, range_to_wall_m(turned, mount));
    }
    // The vertical lobe (+-17.5 deg) adds up to 5 % to a wall's range, the receiver 0.9 m.
    const bool is_close = row.strongest_range_m && *row.strongest_range_m >= lobe_min_m - 0.3 &&
                          *row.strongest_range_m <= 1.05 * lobe_max_m + 1.0;
    close += is_close ? 1 : 0;
    multipath += row.multipath ? 1 : 0;
    // The box's bottom is bright (backscatter 0.3, against 0.003 for the shipped mud bottoms):
    // as a surface patch it can outshine a far or oblique wall, and the truth names it.
    const bool bottom = row.surface == "bottom";
    bottom_strongest += bottom && !is_close && !row.multipath ? 1 : 0;
    agree += is_close || row.multipath || bottom ? 1 : 0;
    // The strongest echo's source lies among the rays (+-2 beamwidths, +-6 deg) and is given
    // whenever there is a strongest echo.
    EXPECT_EQ(row.bearing_offset_rad.has_value(), row.strongest_range_m.has_value());
    if (row.bearing_offset_rad) {
      EXPECT_LE(std::abs(*row.bearing_offset_rad), 6.0 * kPi / 180.0 + 1e-6) << "t = " << row.t_s;
    }
    // The box's groups, or the water surface the simulator adds.
    if (row.strongest_range_m) {
      EXPECT_TRUE(row.surface == "walls" || row.surface == "bottom" ||
                  row.surface == "water_surface")
          << "strongest_surface '" << row.surface << "' at t = " << row.t_s;
    }
  }
  const auto fraction = [&](std::size_t n) {
    return static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(with_hit, 1));
  };
  std::printf(
      "beams with a first hit: %zu of %zu (%.3f); of those: strongest among the wall ranges of the "
      "rays %.3f, "
      "strongest by multipath %.3f, from the bottom otherwise %.3f, any %.3f; max first-hit error "
      "vs box geometry %.2g m\n",
      with_hit, rows.size(), static_cast<double>(with_hit) / static_cast<double>(rows.size()),
      fraction(close), fraction(multipath), fraction(bottom_strongest), fraction(agree),
      max_geometry_error_m);
  // The box is closed and at most ~30 m across from the path: every beam hits a wall in range.
  EXPECT_EQ(with_hit, rows.size());
  EXPECT_LT(max_geometry_error_m, 0.01);
  EXPECT_GE(fraction(agree), 0.9);
}

// The box has no surface farther than ~30 m from the path, so the last bins (45-50 m) hold only
// background noise and weak multipath ghosts: the image there must not be saturated.
TEST(SimulateCommand, BinsBeyondEveryWallAreNotSaturated) {
  const BoxDataset& box = box_dataset();
  const auto beams = io::read_is_log((box.dir / "box_IS.log").string());
  std::vector<double> far;
  for (const auto& beam : beams) {
    for (std::size_t j = 450; j < beam.intensity.size(); ++j) far.push_back(beam.intensity[j]);
  }
  ASSERT_FALSE(far.empty());
  const double median_intensity = median(far);
  std::printf("median intensity of bins 451-500 (45-50 m): %.1f of 255\n", median_intensity);
  EXPECT_LT(median_intensity, 128.0)
      << "the background beyond the walls is saturated: with sonar defaults "
         "(noise_level_db, gain_db, tvg) the noise floor reaches full scale";
}

TEST(SimulateCommand, SameSeedGivesTheSameBytesForAnyThreadCount) {
  const BoxDataset& box = box_dataset();  // 2 threads
  const TempDir tmp;
  simulate(options_for(box.scenario, tmp.path() / "again", 2));
  expect_same_files(box.dir, tmp.path() / "again");
  simulate(options_for(box.scenario, tmp.path() / "one_thread", 1));
  expect_same_files(box.dir, tmp.path() / "one_thread");
}

TEST(SimulateCommand, AnotherSeedGivesAnotherSonarLog) {
  const BoxDataset& box = box_dataset();
  const TempDir tmp;
  SimulateOptions options = options_for(box.scenario, tmp.path() / "seed12");
  options.seed = 12;
  simulate(options);
  EXPECT_NE(read_text((tmp.path() / "seed12" / "box_IS.log").string()),
            read_text((box.dir / "box_IS.log").string()));
  EXPECT_NE(read_text((tmp.path() / "seed12" / "box_DVL.log").string()),
            read_text((box.dir / "box_DVL.log").string()));
  // The truth does not depend on the seed.
  EXPECT_EQ(read_text((tmp.path() / "seed12" / "truth" / "trajectory.tum").string()),
            read_text((box.dir / "truth" / "trajectory.tum").string()));
}

TEST(SimulateCommand, SonarStopsAtStopSAndNavigationRunsOn) {
  // sonar.stop_s: the sonar logs beams for the first 20 s only (as the real St. Pere sonar log
  // ends before its GPS track); the DVL, MTi and truth still cover the whole run.
  const BoxDataset& box = box_dataset();
  const TempDir tmp;
  const std::string scenario = write_box_scenario(tmp.path(), "sonar: {stop_s: 20}\n");
  const SimulateSummary stopped = simulate(options_for(scenario, tmp.path() / "stopped"));
  const double period_s = 13.8 / 200;
  EXPECT_EQ(stopped.beams, static_cast<std::size_t>(std::floor(20.0 / period_s)) + 1);
  EXPECT_GT(box.summary.beams, 2 * stopped.beams);
  EXPECT_EQ(stopped.dvl_samples, box.summary.dvl_samples);
  EXPECT_EQ(stopped.duration_s, box.summary.duration_s);
  const auto times =
      io::read_beam_times_log((tmp.path() / "stopped" / "box_IS_timestamps.log").string());
  ASSERT_EQ(times.size(), stopped.beams);
  const auto all_times = io::read_beam_times_log((box.dir / "box_IS_timestamps.log").string());
  EXPECT_LE(times.back().t_log_s - all_times.front().t_log_s, 20.0);
  // The beams it keeps are the same beams, byte for byte.
  EXPECT_EQ(times.back().t_log_s, all_times[times.size() - 1].t_log_s);
}

TEST(SimulateCommand, StatedCalibrationIsWrittenWhileTheSensorsKeepTheirOwn) {
  // stated_calibration: calibration.yaml says the sonar's clock has no offset and the compass no
  // deviation, while the sonar still logs 0.66 s behind and the MRU deviates (errors left for
  // the estimators). The DVL's scale factor and the water's sound speed change the logs, and
  // calibration.yaml states them (dvl.scale_factor, sonar.range_scale) as no key hides them.
  const BoxDataset& box = box_dataset();
  const TempDir tmp;
  const std::string scenario =
      write_box_scenario(tmp.path(),
                         "sonar: {stop_s: 10, water_sound_speed_mps: 1440}\n"
                         "dvl: {scale_factor: 1.01}\n"
                         "mru: {deviation_cos_deg: 0.62, deviation_sin_deg: -3.39}\n"
                         "stated_calibration:\n"
                         "  mru: {deviation_cos_deg: 0, deviation_sin_deg: 0}\n"
                         "  sonar: {time_offset_s: 0}\n");
  simulate(options_for(scenario, tmp.path() / "stated"));
  const fs::path dir = tmp.path() / "stated";
  const Calibration c = settings::read_calibration((dir / "calibration.yaml").string());
  EXPECT_EQ(c.sonar.time_offset_s, 0.0);
  EXPECT_EQ(c.mru.deviation_cos_deg, 0.0);
  EXPECT_EQ(c.mru.deviation_sin_deg, 0.0);
  EXPECT_EQ(c.dvl.scale_factor, 1.01);
  EXPECT_EQ(c.sonar.range_scale, 1500.0 / 1440.0);
  const Calibration plain = settings::read_calibration((box.dir / "calibration.yaml").string());
  EXPECT_EQ(plain.dvl.scale_factor, 1.0);
  EXPECT_EQ(plain.sonar.range_scale, 1.0);
  EXPECT_EQ(c.mru.yaw_offset_deg, plain.mru.yaw_offset_deg);
  EXPECT_EQ(c.dvl.yaw_deg, plain.dvl.yaw_deg);
  // The log still runs the true 0.66 s behind the truth's beam times.
  const auto beams = io::read_is_log((dir / "box_IS.log").string());
  const std::vector<BeamRow> rows = read_beams_csv((dir / "truth" / "beams.csv").string());
  ASSERT_EQ(rows.size(), beams.size());
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows.front().t_s - beams.front().t_log_s, 0.66, 1e-6);
  // The DVL reads 1 % more than the box's plain run, sample for sample where both have lock.
  const auto dvl = io::read_dvl_log((dir / "box_DVL.log").string());
  const auto plain_dvl = io::read_dvl_log((box.dir / "box_DVL.log").string());
  ASSERT_EQ(dvl.size(), plain_dvl.size());
  // The same noise draws: the difference is 0.01 times the true velocity, 0.5 cm/s at 0.5 m/s.
  std::vector<double> differences_cm_s;
  for (std::size_t i = 0; i < dvl.size(); ++i) {
    if (dvl[i].bottom_vel_status != 1.0 || plain_dvl[i].bottom_vel_status != 1.0) continue;
    differences_cm_s.push_back(
        std::hypot(dvl[i].bottom_vel_cm_s[0] - plain_dvl[i].bottom_vel_cm_s[0],
                   dvl[i].bottom_vel_cm_s[1] - plain_dvl[i].bottom_vel_cm_s[1]));
  }
  ASSERT_GT(differences_cm_s.size(), 50u);
  std::sort(differences_cm_s.begin(), differences_cm_s.end());
  EXPECT_NEAR(differences_cm_s[differences_cm_s.size() / 2], 0.5, 0.05);
}

TEST(SimulateCommand, DeadReckoningRunsOnTheSimulatedDataset) {
  const BoxDataset& box = box_dataset();
  const TempDir tmp;
  RunOptions options;
  options.dataset_dir = box.dir.string();
  options.method = "deadreckoning";
  options.out_dir = (tmp.path() / "result").string();
  const RunOutcome outcome = run(options);
  ASSERT_TRUE(outcome.metrics.has_value());
  std::printf("deadreckoning on the box: mean %.3f m, max %.3f m, final %.3f m\n",
              outcome.metrics->errors.mean_m, outcome.metrics->errors.max_m,
              outcome.metrics->errors.final_m);
  EXPECT_EQ(outcome.metrics->truth, "simulation");
  EXPECT_LT(outcome.metrics->errors.mean_m, 5.0);
  ASSERT_FALSE(outcome.trajectory.empty());
  const double end_s = kStartTime_s + box.summary.duration_s;
  EXPECT_NEAR(outcome.trajectory.back().t_s, end_s, 1.0);
  EXPECT_NEAR(outcome.trajectory.front().t_s, kStartTime_s, 1.0);
  EXPECT_TRUE(fs::is_regular_file(tmp.path() / "result" / "trajectory.tum"));
  EXPECT_TRUE(fs::is_regular_file(tmp.path() / "result" / "metrics.json"));
  // The scenario's segments travel with the dataset (truth/segments.csv) and are scored.
  EXPECT_EQ(read_text((box.dir / "truth" / "segments.csv").string()),
            "name,begin_s,end_s\nfirst_half,0,30\nsecond_half,30,65\n");
  ASSERT_EQ(outcome.metrics->segments.size(), 2u);
  EXPECT_EQ(outcome.metrics->segments[0].first, "first_half");
  EXPECT_EQ(outcome.metrics->segments[1].first, "second_half");
  EXPECT_TRUE(outcome.metrics->segments[0].second && outcome.metrics->segments[1].second);
}

TEST(SimulateCommand, ASectorScanIsLoggedAsItSweepsAndEverySlamMethodRunsOnIt) {
  // A Ping360-like head: 400 steps a turn, 20 ms a step, turning up over the front half
  // (-90 to 90 deg), back and forth. The IS log's transducer angles follow the sweep; the
  // scans are still 400 beams (two sweeps of the sector).
  const TempDir tmp;
  const std::string scenario = write_box_scenario(
      tmp.path(),
      "sonar: {steps_per_revolution: 400, revolution_s: 8, rotation: increasing, "
      "sector_deg: [-90, 90]}\n");
  const fs::path dir = tmp.path() / "dataset";
  simulate(options_for(scenario, dir));
  const std::vector<io::SonarBeamRecord> beams = io::read_is_log((dir / "box_IS.log").string());
  ASSERT_GT(beams.size(), 401u);
  for (std::size_t k = 0; k <= 400; ++k) {
    const std::size_t phase = k % 400;
    const double from_first = 0.9 * static_cast<double>(phase <= 200 ? phase : 400 - phase);
    const double expected_deg = std::fmod(270.0 + from_first, 360.0);
    EXPECT_NEAR(beams[k].transducer_angle_rad * 180.0 / M_PI, expected_deg, 1e-9) << "beam " << k;
  }
  for (const char* method : {"deadreckoning", "robocentric", "worldcentric", "posegraph"}) {
    RunOptions options;
    options.dataset_dir = dir.string();
    options.method = method;
    options.out_dir = (tmp.path() / method).string();
    const RunOutcome outcome = run(options);
    ASSERT_TRUE(outcome.metrics.has_value()) << method;
    std::printf("sector scan, %s: mean error %.3f m\n", method, outcome.metrics->errors.mean_m);
    EXPECT_LT(outcome.metrics->errors.mean_m, 5.0) << method;
  }
}

TEST(SimulateCommand, ADvlWithYToStarboardIsReadThroughItsCalibration) {
  // The dataset states the mirrored axis and dead reckoning follows the box as with the default
  // DVL; the same logs read as if y were to port (a calibration that does not say it) do not.
  const TempDir tmp;
  const std::string scenario =
      write_box_scenario(tmp.path(), "dvl: {mount: {yaw_deg: 90, y_axis: starboard}}\n");
  const fs::path dir = tmp.path() / "dataset";
  simulate(options_for(scenario, dir));
  EXPECT_NE(read_text((dir / "calibration.yaml").string()).find("y_axis: starboard"),
            std::string::npos);
  RunOptions options;
  options.dataset_dir = dir.string();
  options.method = "deadreckoning";
  options.out_dir = (tmp.path() / "stated").string();
  const double stated_m = run(options).metrics->errors.mean_m;
  std::string port = read_text((dir / "calibration.yaml").string());
  port.replace(port.find("  y_axis: starboard\n"), std::string("  y_axis: starboard\n").size(), "");
  options.calibration_path = write_text(tmp.file("port.yaml"), port);
  options.out_dir = (tmp.path() / "port").string();
  const double port_m = run(options).metrics->errors.mean_m;
  std::printf("box, DVL y to starboard: dead reckoning %.3f m read as stated, %.3f m as port\n",
              stated_m, port_m);
  // Measured: 1.38 m against 15.2 m (the default box's dead reckoning: about 1.1 m). A DVL whose
  // frame is misread runs the vehicle backwards along x.
  EXPECT_LT(stated_m, 2.0);
  EXPECT_GT(port_m, 5.0 * stated_m);
}

// The detections file is the real file's layout: keyframe k is the k-th complete revolution (the
// angle index from 199 down to 0), beam_row the beam's row in *_IS_timestamps.log, and its bins
// are exactly the detector's on the IS log's profile; beams outside a revolution have no rows.
// The real reader reads it, and the front end reads the dataset through it.
TEST(SimulateCommand, DetectionsAreTheDetectorOnEveryProfileInTheRealLayout) {
  const BoxDataset& box = box_dataset();
  const auto beams = io::read_is_log((box.dir / "box_IS.log").string());
  const auto times = io::read_beam_times_log((box.dir / "box_IS_timestamps.log").string());
  ASSERT_EQ(times.size(), beams.size());
  for (std::size_t i = 0; i < beams.size(); ++i) {
    ASSERT_EQ(times[i].t_log_s, beams[i].t_log_s) << "beam " << i;
    ASSERT_EQ(times[i].sensor_time_ms, beams[i].sensor_time_ms) << "beam " << i;
  }
  const auto rows = io::read_detections((box.dir / "box_detections.csv.gz").string());
  ASSERT_FALSE(rows.empty());
  const double step_rad = 2.0 * kPi / 200.0;
  const auto angle_index = [&](std::size_t i) {
    return static_cast<int>(std::lround(beams[i].transducer_angle_rad / step_rad)) % 200;
  };
  // The first complete revolution starts at the first beam whose angle index is 199.
  std::size_t start = 0;
  while (angle_index(start) != 199) ++start;
  const std::size_t revolutions = (beams.size() - start) / 200;
  ASSERT_GE(revolutions, 1u);
  std::map<std::size_t, std::vector<const io::DetectionRecord*>> by_beam;
  for (const io::DetectionRecord& r : rows) {
    by_beam[static_cast<std::size_t>(r.beam_row)].push_back(&r);
  }
  const sim::Scenario scenario = settings::read_scenario(box.scenario);
  std::size_t detected_beams = 0;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const bool inside = i >= start && i < start + 200 * revolutions;
    const auto found = by_beam.find(i);
    if (!inside) {
      EXPECT_TRUE(found == by_beam.end()) << "beam " << i << " is outside every revolution";
      continue;
    }
    const std::vector<int> bins = sim::detect_bins(beams[i].intensity, 0.1, scenario.detections);
    const std::size_t listed = found == by_beam.end() ? 0 : found->second.size();
    ASSERT_EQ(listed, bins.size()) << "beam " << i;
    detected_beams += listed > 0;
    for (std::size_t k = 0; k < listed; ++k) {
      const io::DetectionRecord& r = *found->second[k];
      ASSERT_EQ(r.keyframe, static_cast<int>((i - start) / 200) + 1) << "beam " << i;
      ASSERT_EQ(r.angle_idx, angle_index(i)) << "beam " << i;
      ASSERT_NEAR(r.angle_rad, r.angle_idx * step_rad, 1e-5) << "beam " << i;
      ASSERT_EQ(r.t_log_s, beams[i].t_log_s) << "beam " << i;
      ASSERT_NEAR(r.range_m, (bins[k] + 1) * 0.1, 1e-9) << "beam " << i;
    }
  }
  // The walls of the box lie within 22 m of every point of the path: most beams see one.
  EXPECT_GT(detected_beams, 100u * revolutions);

  // The front end reads the dataset through the detections as through the raw profiles.
  SlamConfig config;
  config.segmentation.source = SonarSource::kDetections;
  const dataset::DatasetFiles files = dataset::find_dataset_files(box.dir.string());
  const Calibration calibration = dataset::load_calibration(files);
  const dataset::SonarInput sonar =
      dataset::load_sonar_readings(files, calibration, config.segmentation);
  EXPECT_EQ(sonar.source, "detections");
  ASSERT_EQ(sonar.beams.size(), beams.size());
  std::size_t with_readings = 0;
  for (const BeamReadings& b : sonar.beams) with_readings += !b.readings.empty();
  EXPECT_EQ(with_readings, detected_beams);
  // A range scale in the calibration divides every reading's range.
  Calibration scaled = calibration;
  scaled.sonar.range_scale = 1.25;
  const dataset::SonarInput shorter =
      dataset::load_sonar_readings(files, scaled, config.segmentation);
  ASSERT_EQ(shorter.beams.size(), sonar.beams.size());
  for (std::size_t i = 0; i < sonar.beams.size(); ++i) {
    ASSERT_EQ(shorter.beams[i].readings.size(), sonar.beams[i].readings.size());
    for (std::size_t k = 0; k < sonar.beams[i].readings.size(); ++k) {
      ASSERT_NEAR(shorter.beams[i].readings[k].range_m * 1.25, sonar.beams[i].readings[k].range_m,
                  1e-12);
    }
  }
  config.segmentation.source = SonarSource::kRaw;
  EXPECT_EQ(dataset::load_sonar_readings(files, calibration, config.segmentation).source, "IS log");
}

// The message of the InputError that simulate(options) throws ("" and a failure when none).
std::string simulate_error(const SimulateOptions& options) {
  try {
    simulate(options);
  } catch (const io::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << options.scenario_path;
  return "";
}

TEST(SimulateCommand, MissingMeshNamesItAndWritesNothing) {
  const TempDir tmp;
  const std::string scenario = write_box_scenario(tmp.path());
  fs::remove(tmp.path() / "box.obj");
  const std::string message = simulate_error(options_for(scenario, tmp.path() / "out"));
  const std::string mesh = (tmp.path() / "box.obj").string();
  EXPECT_NE(message.find(mesh), std::string::npos) << message << "\nexpected " << mesh;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1)
      << "only scenario.yaml should be there";
}

TEST(SimulateCommand, EmptyMeshIsBadInput) {
  const TempDir tmp;
  const std::string scenario = write_box_scenario(tmp.path());
  write_text((tmp.path() / "box.obj").string(), "");
  const std::string message = simulate_error(options_for(scenario, tmp.path() / "out"));
  EXPECT_NE(message.find((tmp.path() / "box.obj").string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

TEST(SimulateCommand, BadScenarioLeavesAnExistingDatasetUntouched) {
  const TempDir tmp;
  const fs::path out = tmp.path() / "out";
  fs::create_directories(out);
  write_text((out / "marker.txt").string(), "an earlier dataset\n");
  const std::string scenario = write_box_scenario(tmp.path(), "sonar: {bems: 3}\n");
  const std::string message = simulate_error(options_for(scenario, out));
  EXPECT_NE(message.find(scenario + ":13:"), std::string::npos) << message;
  EXPECT_NE(message.find("key 'sonar.bems'"), std::string::npos) << message;
  EXPECT_EQ(read_text((out / "marker.txt").string()), "an earlier dataset\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
}

TEST(SimulateCommand, NewDatasetReplacesAnEarlierOneWhole) {
  const TempDir tmp;
  const fs::path out = tmp.path() / "out";
  // A short run with a cheap sonar is enough here; the earlier dataset is of a scenario "old".
  const std::string scenario = write_box_scenario(tmp.path(), "sonar: {rays_vertical: 2}\n");
  std::string old_scenario = read_text(scenario);
  old_scenario.replace(old_scenario.find("name: box"), 9, "name: old");
  simulate(options_for(write_text(tmp.file("old.yaml"), old_scenario), out));
  ASSERT_TRUE(fs::exists(out / "old_IS.log"));
  simulate(options_for(scenario, out));
  EXPECT_FALSE(fs::exists(out / "old_IS.log"));
  EXPECT_TRUE(fs::is_regular_file(out / "box_IS.log"));
  EXPECT_NO_THROW(dataset::find_dataset_files(out.string()));
}

// docs/simulator.md: the vehicle "stops at the last waypoint". A last leg shorter than the turning
// circle (0.5 m/s at 0.15 rad/s: radius 3.3 m) after a corner must not leave it circling.
TEST(SimulateCommand, VehicleStopsAtTheLastWaypointAfterAShortLastLeg) {
  const TempDir tmp;
  fs::create_directories(tmp.path());
  io::write_obj((tmp.path() / "box.obj").string(), box_basin());
  const std::string scenario = write_text(tmp.file("short_leg.yaml"),
                                          "seed: 1\n"
                                          "scene: {mesh: box.obj}\n"
                                          "vehicle:\n"
                                          "  depth_m: 1.5\n"
                                          "  speed_mps: 0.5\n"
                                          "  path: [[-6, -3], [6, -3], [6, 3], [-6, 3], [-6, 0]]\n"
                                          "sonar: {rays_horizontal: 1, rays_vertical: 1, bins: 10,"
                                          " steps_per_revolution: 4}\n");
  const SimulateSummary summary = simulate(options_for(scenario, tmp.path() / "out"));
  const auto truth = io::read_tum((tmp.path() / "out" / "truth" / "trajectory.tum").string());
  ASSERT_FALSE(truth.empty());
  const double length_m = 12.0 + 6.0 + 12.0 + 3.0;
  const double end_distance_m = std::hypot(truth.back().x_m + 6.0, truth.back().y_m - 0.0);
  std::printf("short last leg: %.1f s for a %.0f m path, ends %.2f m from the last waypoint\n",
              summary.duration_s, length_m, end_distance_m);
  EXPECT_LT(summary.duration_s, 1.5 * length_m / kSpeed_mps);
  EXPECT_LT(end_distance_m, 1.0);
}

using testing::CliResult;
using testing::run_msislab;
using testing::shell_quote;

TEST(SimulateCli, GoodScenarioExitsZero) {
  const TempDir tmp;
  const std::string scenario = write_box_scenario(tmp.path() / "scene");
  const fs::path out = tmp.path() / "dataset";
  const CliResult result =
      run_msislab("simulate " + shell_quote(scenario) + " --out " + shell_quote(out.string()), tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  // One warning: the box's bottom is bright on purpose (backscatter 0.3, the walls 0.8).
  EXPECT_EQ(result.err.rfind("msislab: " + scenario + ":3: warning: key 'scene': the floor's", 0),
            0u)
      << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.out.find("wrote"), std::string::npos) << result.out;
  for (const char* name : kDatasetFiles) {
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
}

TEST(SimulateCli, BadScenarioExitsTwoWithOneLine) {
  const TempDir tmp;
  const std::string scenario = write_box_scenario(tmp.path() / "scene", "vehicle_speed: 3\n");
  const fs::path out = tmp.path() / "dataset";
  const CliResult result =
      run_msislab("simulate " + shell_quote(scenario) + " --out " + shell_quote(out.string()), tmp);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(scenario + ":13:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("vehicle_speed"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace msislab::app
