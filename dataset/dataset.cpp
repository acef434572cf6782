#include "dataset/dataset.hpp"

#include <filesystem>

#include "io/geodesy.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "io/text_lines.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::dataset {

namespace fs = std::filesystem;

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void assign_unique(std::optional<std::string>& slot, const fs::path& path, const std::string& dir,
                   const std::string& pattern) {
  if (slot) {
    io::fail_file(dir, "more than one " + pattern + " file (" +
                           fs::path(*slot).filename().string() + ", " + path.filename().string() +
                           ")");
  }
  slot = path.string();
}

std::optional<std::string> existing(const fs::path& path) {
  if (fs::is_regular_file(path)) return path.string();
  return std::nullopt;
}

const std::string& require(const std::optional<std::string>& file, const DatasetFiles& files,
                           const std::string& pattern) {
  if (!file) io::fail_file(files.dir, "no " + pattern + " file in the dataset directory");
  return *file;
}
}  // namespace

DatasetFiles find_dataset_files(const std::string& dir) {
  if (fs::is_regular_file(dir)) {
    const std::string extension = fs::path(dir).extension().string();
    io::fail_file(dir, extension == ".yaml" || extension == ".yml"
                           ? "is a file, not a dataset directory (a scenario? simulate it first: "
                             "msislab simulate " +
                                 dir + " --out DIR, then give DIR)"
                           : "is a file, not a dataset directory");
  }
  if (!fs::is_directory(dir)) io::fail_file(dir, "dataset directory does not exist");
  DatasetFiles files;
  files.dir = dir;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (ends_with(name, "_DVL.log")) assign_unique(files.dvl, entry.path(), dir, "*_DVL.log");
    if (ends_with(name, "_MTi.log")) assign_unique(files.mti, entry.path(), dir, "*_MTi.log");
    if (ends_with(name, "_DGPS.log")) assign_unique(files.gps, entry.path(), dir, "*_DGPS.log");
    if (ends_with(name, "_SETUP.log")) assign_unique(files.setup, entry.path(), dir, "*_SETUP.log");
    if (ends_with(name, "_IS.log")) assign_unique(files.is_log, entry.path(), dir, "*_IS.log");
    if (ends_with(name, "_IS_timestamps.log")) {
      assign_unique(files.beam_times, entry.path(), dir, "*_IS_timestamps.log");
    }
    if (ends_with(name, "_detections.csv") || ends_with(name, "_detections.csv.gz")) {
      assign_unique(files.detections, entry.path(), dir, "*_detections.csv[.gz]");
    }
  }
  files.calibration = existing(fs::path(dir) / "calibration.yaml");
  files.navigation_noise = existing(fs::path(dir) / "navigation_noise.yaml");
  files.truth_trajectory = existing(fs::path(dir) / "truth" / "trajectory.tum");
  files.truth_beams = existing(fs::path(dir) / "truth" / "beams.csv");
  files.truth_segments = existing(fs::path(dir) / "truth" / "segments.csv");
  return files;
}

std::vector<TimeSegment> load_truth_segments(const DatasetFiles& files) {
  std::vector<TimeSegment> segments;
  if (!files.truth_segments) return segments;
  const std::string& path = *files.truth_segments;
  io::for_each_csv_row(path, "name,begin_s,end_s", [&](std::string_view row, std::size_t line) {
    const auto fields = io::split_csv<3>(row, path, line);
    TimeSegment segment{std::string(fields[0]),
                        io::parse_finite(fields[1], {path, line, 2, "begin_s"}),
                        io::parse_finite(fields[2], {path, line, 3, "end_s"})};
    if (segment.name.empty()) io::fail_at(path, line, "empty segment name");
    for (const TimeSegment& earlier : segments) {
      if (earlier.name == segment.name)
        io::fail_at(path, line, "segment '" + segment.name + "' twice");
    }
    if (!(segment.end_s > segment.begin_s)) {
      io::fail_at(path, line, "segment '" + segment.name + "' ends before it begins");
    }
    segments.push_back(segment);
  });
  return segments;
}

Calibration load_calibration(const DatasetFiles& files) {
  return files.calibration ? settings::read_calibration(*files.calibration) : Calibration{};
}

NavigationLog load_navigation(const DatasetFiles& files, const Calibration& calibration) {
  const std::vector<io::DvlRecord> dvl = io::read_dvl_log(require(files.dvl, files, "*_DVL.log"));
  return navigation_of(dvl, io::read_mti_log(require(files.mti, files, "*_MTi.log")), calibration);
}

NavigationLog navigation_of(const std::vector<io::DvlRecord>& dvl,
                            const std::vector<io::MtiRecord>& mti, const Calibration& calibration) {
  NavigationLog log;
  const Eigen::Matrix2d R_vehicle_from_dvl = R_vehicle_dvl(calibration.dvl);
  for (const io::DvlRecord& row : dvl) {
    if (row.bottom_vel_status != 1.0) {
      ++log.dvl_rows_without_bottom_lock;
      continue;
    }
    const Eigen::Vector2d v_dvl_mps(row.bottom_vel_cm_s[0] / 100.0, row.bottom_vel_cm_s[1] / 100.0);
    log.dvl.push_back({row.t_log_s, R_vehicle_from_dvl * v_dvl_mps / calibration.dvl.scale_factor});
  }
  for (const io::MtiRecord& row : mti) {
    log.heading.push_back({row.t_log_s, vehicle_yaw_from_mru(row.yaw_deg, calibration.mru)});
  }
  return log;
}

std::vector<PositionFix> load_gps_fixes(const DatasetFiles& files, const Calibration& calibration) {
  return gps_fixes_of(io::read_gps_log(require(files.gps, files, "*_DGPS.log")), calibration);
}

std::vector<PositionFix> gps_fixes_of(const std::vector<io::GpsRecord>& rows,
                                      const Calibration& calibration) {
  const io::LocalProjection projection(calibration.frame);
  std::vector<PositionFix> fixes;
  fixes.reserve(rows.size());
  for (const io::GpsRecord& row : rows) {
    if (row.status <= 0.0) continue;
    fixes.push_back({row.t_log_s, projection.to_local(io::nmea_to_degrees(row.latitude_nmea),
                                                      io::nmea_to_degrees(row.longitude_nmea))});
  }
  return fixes;
}

}  // namespace msislab::dataset
