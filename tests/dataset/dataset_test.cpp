// Dataset directories: files found by suffix with any prefix, duplicates and missing directories
// rejected, and the navigation and GPS streams loaded through the calibration (on small logs
// written with the io writers, then on the real St. Pere logs).
#include "dataset/dataset.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "geometry/angles.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "test_support.hpp"

namespace msislab::dataset {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_text;

// Expects action() to throw InputError whose message contains every one of `words`.
template <typename Action>
void expect_input_error(Action action, const std::vector<std::string>& words) {
  try {
    action();
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    for (const std::string& word : words) {
      EXPECT_NE(message.find(word), std::string::npos) << message << "\nno '" << word << "'";
    }
  }
}

io::DvlRecord dvl_row(double t_s, double vx_cm_s, double vy_cm_s, double status) {
  io::DvlRecord row;
  row.t_log_s = t_s;
  row.bottom_vel_cm_s = {vx_cm_s, vy_cm_s, 0.5};
  row.bottom_vel_status = status;
  row.water_vel_cm_s = {99.0, -99.0, 1.0};  // never used for navigation
  row.water_vel_status = 1.0;
  return row;
}

io::MtiRecord mti_row(double t_s, double yaw_deg) {
  io::MtiRecord row;
  row.t_log_s = t_s;
  row.yaw_deg = yaw_deg;
  row.roll_deg = 1.5;
  return row;
}

io::GpsRecord gps_row(double t_s, double lat_deg, double lon_deg, double status) {
  io::GpsRecord row;
  row.t_log_s = t_s;
  row.latitude_nmea = io::degrees_to_nmea(lat_deg);
  row.longitude_nmea = io::degrees_to_nmea(lon_deg);
  row.status = status;
  return row;
}

TEST(DatasetFiles, FindsEveryFileBySuffixWithAnyPrefix) {
  const TempDir dir;
  fs::create_directories(dir.path() / "truth");
  for (const char* name : {"x_DVL.log", "x_MTi.log", "some.prefix_DGPS.log", "_IS_timestamps.log",
                           "abc_detections.csv.gz", "calibration.yaml", "truth/trajectory.tum",
                           "notes.txt", "x_DVL.log.bak"}) {
    write_text(dir.file(name), "");
  }
  const DatasetFiles files = find_dataset_files(dir.path().string());
  EXPECT_EQ(files.dir, dir.path().string());
  EXPECT_EQ(files.dvl, dir.file("x_DVL.log"));
  EXPECT_EQ(files.mti, dir.file("x_MTi.log"));
  EXPECT_EQ(files.gps, dir.file("some.prefix_DGPS.log"));
  EXPECT_EQ(files.beam_times, dir.file("_IS_timestamps.log"));
  EXPECT_EQ(files.detections, dir.file("abc_detections.csv.gz"));
  EXPECT_EQ(files.calibration, dir.file("calibration.yaml"));
  EXPECT_EQ(files.truth_trajectory, (dir.path() / "truth" / "trajectory.tum").string());
  // Absent ones stay empty; *_IS_timestamps.log is not a raw *_IS.log.
  EXPECT_FALSE(files.is_log.has_value());
  EXPECT_FALSE(files.setup.has_value());
  EXPECT_FALSE(files.truth_beams.has_value());
}

TEST(DatasetFiles, RawSonarLogUncompressedDetectionsAndSetup) {
  const TempDir dir;
  fs::create_directories(dir.path() / "truth");
  for (const char* name :
       {"r_IS.log", "r_IS_timestamps.log", "r_detections.csv", "r_SETUP.log", "truth/beams.csv"}) {
    write_text(dir.file(name), "");
  }
  // A directory with a log's name is not a log.
  fs::create_directories(dir.path() / "d_DVL.log");
  const DatasetFiles files = find_dataset_files(dir.path().string());
  EXPECT_EQ(files.is_log, dir.file("r_IS.log"));
  EXPECT_EQ(files.beam_times, dir.file("r_IS_timestamps.log"));
  EXPECT_EQ(files.detections, dir.file("r_detections.csv"));
  EXPECT_EQ(files.setup, dir.file("r_SETUP.log"));
  EXPECT_EQ(files.truth_beams, (dir.path() / "truth" / "beams.csv").string());
  EXPECT_FALSE(files.dvl.has_value());
  EXPECT_FALSE(files.mti.has_value());
  EXPECT_FALSE(files.gps.has_value());
  EXPECT_FALSE(files.calibration.has_value());
  EXPECT_FALSE(files.truth_trajectory.has_value());
}

TEST(DatasetFiles, TwoFilesWithOneSuffixAreAnError) {
  const TempDir dir;
  write_text(dir.file("a_DVL.log"), "");
  write_text(dir.file("b_DVL.log"), "");
  expect_input_error([&] { find_dataset_files(dir.path().string()); },
                     {dir.path().string(), "a_DVL.log", "b_DVL.log"});
}

TEST(DatasetFiles, TwoDetectionFilesAreAnError) {
  const TempDir dir;
  write_text(dir.file("a_detections.csv"), "");
  write_text(dir.file("a_detections.csv.gz"), "");
  expect_input_error([&] { find_dataset_files(dir.path().string()); },
                     {"a_detections.csv", "a_detections.csv.gz"});
}

TEST(DatasetFiles, MissingDirectoryIsAnError) {
  const TempDir dir;
  const std::string missing = dir.file("no_such_dataset");
  expect_input_error([&] { find_dataset_files(missing); }, {missing});
  // A file is not a dataset directory either.
  const std::string file = write_text(dir.file("x_DVL.log"), "");
  expect_input_error([&] { find_dataset_files(file); }, {file});
}

TEST(LoadTruthSegments, ReadsTheWindowsInFileOrderAndRejectsBadRows) {
  const TempDir dir;
  fs::create_directories(dir.path() / "truth");
  EXPECT_TRUE(load_truth_segments(find_dataset_files(dir.path().string())).empty());
  const std::string path = dir.file("truth/segments.csv");
  write_text(path, "name,begin_s,end_s\nloop,0,1890\ncanal,1890,3400.5\n");
  const std::vector<TimeSegment> segments =
      load_truth_segments(find_dataset_files(dir.path().string()));
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].name, "loop");
  EXPECT_EQ(segments[0].end_s, 1890.0);
  EXPECT_EQ(segments[1].name, "canal");
  EXPECT_EQ(segments[1].begin_s, 1890.0);
  EXPECT_EQ(segments[1].end_s, 3400.5);
  const auto bad = [&](const std::string& rows, const std::vector<std::string>& words) {
    write_text(path, "name,begin_s,end_s\n" + rows);
    const DatasetFiles files = find_dataset_files(dir.path().string());
    expect_input_error([&] { load_truth_segments(files); }, words);
  };
  bad("loop,0,10\nloop,10,20\n", {path + ":3", "twice"});
  bad("loop,10,5\n", {path + ":2", "ends before it begins"});
  bad("loop,0,nan\n", {path + ":2", "end_s"});
  bad("loop,0\n", {path + ":2"});
  bad(",0,10\n", {path + ":2", "empty segment name"});
  write_text(path, "name,start,end\n");
  expect_input_error([&] { load_truth_segments(find_dataset_files(dir.path().string())); },
                     {path + ":1", "wrong header"});
}

TEST(LoadCalibration, DefaultsWithoutFileElseTheFile) {
  const TempDir dir;
  DatasetFiles files = find_dataset_files(dir.path().string());
  EXPECT_EQ(load_calibration(files).dvl.yaw_deg, 293.5);
  write_text(dir.file("calibration.yaml"), "dvl:\n  yaw_deg: 10\n");
  files = find_dataset_files(dir.path().string());
  EXPECT_EQ(load_calibration(files).dvl.yaw_deg, 10.0);
  write_text(dir.file("calibration.yaml"), "dvl:\n  yaw_dg: 10\n");
  files = find_dataset_files(dir.path().string());
  expect_input_error([&] { load_calibration(files); },
                     {dir.file("calibration.yaml") + ":2:", "dvl.yaw_dg"});
}

TEST(LoadNavigation, DropsRowsWithoutBottomLockAndAppliesTheMounts) {
  const TempDir dir;
  io::write_dvl_log(dir.file("n_DVL.log"),
                    {dvl_row(100.0, 10.0, 0.0, 1.0), dvl_row(100.7, 50.0, 50.0, 0.0),
                     dvl_row(101.3, -4.0, 12.5, 1.0), dvl_row(102.0, 3.0, 3.0, 2.0),
                     dvl_row(102.6, 0.0, 20.0, 1.0)});
  io::write_mti_log(dir.file("n_MTi.log"),
                    {mti_row(100.0, 86.0), mti_row(100.1, 176.0), mti_row(100.2, 131.0),
                     mti_row(100.3, 41.0), mti_row(100.4, -94.5)});
  const DatasetFiles files = find_dataset_files(dir.path().string());
  const Calibration calibration = load_calibration(files);
  const NavigationLog log = load_navigation(files, calibration);

  ASSERT_EQ(log.dvl.size(), 3u);
  EXPECT_EQ(log.dvl_rows_without_bottom_lock, 2);
  EXPECT_EQ(log.dvl[0].t_s, 100.0);
  EXPECT_EQ(log.dvl[1].t_s, 101.3);
  EXPECT_EQ(log.dvl[2].t_s, 102.6);
  // cm/s -> m/s, then Rz(293.5 deg) from the DVL frame to the vehicle frame.
  const double a = 293.5 * kDegToRad;
  EXPECT_NEAR(log.dvl[0].v_vehicle_mps.x(), 0.1 * std::cos(a), 1e-15);
  EXPECT_NEAR(log.dvl[0].v_vehicle_mps.y(), 0.1 * std::sin(a), 1e-15);
  EXPECT_NEAR(log.dvl[1].v_vehicle_mps.x(), -0.04 * std::cos(a) - 0.125 * std::sin(a), 1e-15);
  EXPECT_NEAR(log.dvl[1].v_vehicle_mps.y(), -0.04 * std::sin(a) + 0.125 * std::cos(a), 1e-15);
  EXPECT_NEAR(log.dvl[2].v_vehicle_mps.x(), -0.2 * std::sin(a), 1e-15);
  EXPECT_NEAR(log.dvl[2].v_vehicle_mps.y(), 0.2 * std::cos(a), 1e-15);

  // psi = pi/2 - (yaw_mti - 86 deg): north, east, north-east, north-west, just west of south.
  ASSERT_EQ(log.heading.size(), 5u);
  const double mti_yaw_deg[] = {86.0, 176.0, 131.0, 41.0, -94.5};
  const double expected_yaw_rad[] = {kPi / 2.0, 0.0, kPi / 4.0, 3.0 * kPi / 4.0,
                                     -kPi / 2.0 + 0.5 * kDegToRad};
  for (std::size_t i = 0; i < log.heading.size(); ++i) {
    EXPECT_NEAR(log.heading[i].yaw_rad, expected_yaw_rad[i], 1e-12) << i;
    EXPECT_EQ(log.heading[i].yaw_rad, vehicle_yaw_from_mru(mti_yaw_deg[i], calibration.mru)) << i;
  }
  EXPECT_EQ(log.heading[3].t_s, 100.3);
}

// The DVL's scale factor (calibration.yaml dvl.scale_factor): it reads that many times the true
// velocity, so every velocity is divided by it.
TEST(LoadNavigation, DividesTheVelocitiesByTheDvlScaleFactor) {
  const TempDir dir;
  io::write_dvl_log(dir.file("n_DVL.log"), {dvl_row(10.0, 30.0, -12.0, 1.0)});
  io::write_mti_log(dir.file("n_MTi.log"), {mti_row(10.0, 0.0)});
  const DatasetFiles files = find_dataset_files(dir.path().string());
  Calibration calibration = load_calibration(files);
  const NavigationLog plain = load_navigation(files, calibration);
  calibration.dvl.scale_factor = 1.25;
  const NavigationLog scaled = load_navigation(files, calibration);
  ASSERT_EQ(scaled.dvl.size(), 1u);
  EXPECT_NEAR((scaled.dvl[0].v_vehicle_mps * 1.25 - plain.dvl[0].v_vehicle_mps).norm(), 0.0, 1e-15);
}

TEST(LoadNavigation, UsesTheCalibrationFile) {
  const TempDir dir;
  io::write_dvl_log(dir.file("n_DVL.log"), {dvl_row(10.0, 30.0, 0.0, 1.0)});
  io::write_mti_log(dir.file("n_MTi.log"), {mti_row(10.0, 0.0)});
  write_text(dir.file("calibration.yaml"), "mru: {yaw_offset_deg: 0}\ndvl: {yaw_deg: 90}\n");
  const DatasetFiles files = find_dataset_files(dir.path().string());
  const NavigationLog log = load_navigation(files, load_calibration(files));
  ASSERT_EQ(log.dvl.size(), 1u);
  EXPECT_NEAR(log.dvl[0].v_vehicle_mps.x(), 0.0, 1e-15);
  EXPECT_NEAR(log.dvl[0].v_vehicle_mps.y(), 0.3, 1e-15);
  ASSERT_EQ(log.heading.size(), 1u);
  EXPECT_NEAR(log.heading[0].yaw_rad, kPi / 2.0, 1e-15);
}

TEST(LoadNavigation, RequiresBothLogs) {
  const TempDir dir;
  io::write_mti_log(dir.file("n_MTi.log"), {mti_row(10.0, 0.0)});
  DatasetFiles files = find_dataset_files(dir.path().string());
  expect_input_error([&] { load_navigation(files, Calibration{}); },
                     {dir.path().string(), "_DVL.log"});
  fs::remove(dir.file("n_MTi.log"));
  io::write_dvl_log(dir.file("n_DVL.log"), {dvl_row(10.0, 30.0, 0.0, 1.0)});
  files = find_dataset_files(dir.path().string());
  expect_input_error([&] { load_navigation(files, Calibration{}); },
                     {dir.path().string(), "_MTi.log"});
}

TEST(LoadGpsFixes, DropsStatusZeroAndProjectsToTheLocalFrame) {
  const TempDir dir;
  const Calibration calibration;
  const double lat0 = calibration.frame.origin_latitude_deg;
  const double lon0 = calibration.frame.origin_longitude_deg;
  io::write_gps_log(
      dir.file("g_DGPS.log"),
      {gps_row(50.0, lat0, lon0, 1.0), gps_row(51.0, 43.0, 4.0, 0.0),
       gps_row(52.0, lat0 + 0.001, lon0, 2.0), gps_row(53.0, 42.20200, 3.10750, 1.0)});
  const std::vector<PositionFix> fixes =
      load_gps_fixes(find_dataset_files(dir.path().string()), calibration);
  ASSERT_EQ(fixes.size(), 3u);
  EXPECT_EQ(fixes[0].t_s, 50.0);
  EXPECT_EQ(fixes[1].t_s, 52.0);
  EXPECT_EQ(fixes[2].t_s, 53.0);
  EXPECT_NEAR(fixes[0].p_world_m.norm(), 0.0, 1e-6);
  // UTM 31N differences from cs2cs (see geodesy_test.cpp): 0.001 deg north, and a point to the SE.
  EXPECT_NEAR(fixes[1].p_world_m.x(), 508644.804064182 - 508644.940391571, 1e-3);
  EXPECT_NEAR(fixes[1].p_world_m.y(), 4672515.096848746 - 4672404.064009894, 1e-3);
  EXPECT_NEAR(fixes[2].p_world_m.x(), 508874.682398491 - 508644.940391571, 1e-3);
  EXPECT_NEAR(fixes[2].p_world_m.y(), 4672210.042103519 - 4672404.064009894, 1e-3);
}

TEST(LoadGpsFixes, RequiresTheGpsLog) {
  const TempDir dir;
  expect_input_error(
      [&] { load_gps_fixes(find_dataset_files(dir.path().string()), Calibration{}); },
      {dir.path().string(), "_DGPS.log"});
}

TEST(StPereDataset, FilesAndStreams) {
  MSISLAB_REQUIRE_STPERE();
  const DatasetFiles files = find_dataset_files(testing::stpere_dir());
  const std::string prefix = (fs::path(testing::stpere_dir()) / "_040825_1735_").string();
  EXPECT_EQ(files.dvl, prefix + "DVL.log");
  EXPECT_EQ(files.mti, prefix + "MTi.log");
  EXPECT_EQ(files.gps, prefix + "DGPS.log");
  EXPECT_EQ(files.setup, prefix + "SETUP.log");
  EXPECT_EQ(files.beam_times, prefix + "IS_timestamps.log");
  EXPECT_EQ(files.detections, prefix + "detections.csv.gz");
  EXPECT_FALSE(files.is_log.has_value());
  EXPECT_FALSE(files.truth_trajectory.has_value());

  const Calibration calibration = load_calibration(files);
  const NavigationLog log = load_navigation(files, calibration);
  EXPECT_EQ(log.dvl.size(), 4961u);
  EXPECT_EQ(log.dvl_rows_without_bottom_lock, 84);
  EXPECT_EQ(log.heading.size(), 33457u);

  const std::vector<PositionFix> fixes = load_gps_fixes(files, calibration);
  ASSERT_EQ(fixes.size(), 3342u);
  EXPECT_NEAR(fixes.front().p_world_m.x(), 0.0, 1e-6);
  EXPECT_NEAR(fixes.front().p_world_m.y(), 0.0, 1e-6);
  Eigen::Vector2d lo = fixes.front().p_world_m;
  Eigen::Vector2d hi = lo;
  for (const PositionFix& fix : fixes) {
    lo = lo.cwiseMin(fix.p_world_m);
    hi = hi.cwiseMax(fix.p_world_m);
  }
  const Eigen::Vector2d span = hi - lo;
  std::printf("St. Pere GPS track: %.1f m (east) x %.1f m (north)\n", span.x(), span.y());
  // "About 240 x 120 m" (README): 240 m north-south by 120 m east-west. The raw NMEA extremes
  // (42.20160-42.20375 N, 3.10470-3.10615 E) span about 239 m of latitude and 120 m of longitude.
  EXPECT_GT(span.y(), 200.0);
  EXPECT_LT(span.y(), 280.0);
  EXPECT_GT(span.x(), 90.0);
  EXPECT_LT(span.x(), 150.0);
}

}  // namespace
}  // namespace msislab::dataset
