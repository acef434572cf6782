#include "dataset/sonar_readings.hpp"

#include <cmath>

#include "io/detections.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::dataset {

namespace {

/// The beam's readings, each range divided by the mount's range scale (calibration.yaml).
std::vector<SonarReading> readings_of(double t_s, const std::vector<double>& ranges_m,
                                      double bearing_rad, const SonarMount& mount,
                                      const SegmentationConfig& config) {
  std::vector<SonarReading> readings;
  for (const double range_m : ranges_m) {
    readings.push_back({t_s, range_m / mount.range_scale, bearing_rad, config.sigma_range_m,
                        config.sigma_bearing_rad});
  }
  return readings;
}

SonarInput from_is_log(const std::vector<io::SonarBeamRecord>& beams, const io::SonarSetup& setup,
                       const SonarMount& mount, const SegmentationConfig& config) {
  SonarInput input;
  input.source = "IS log";
  for (const io::SonarBeamRecord& beam : beams) {
    const double bearing = sonar_bearing_in_vehicle(beam.transducer_angle_rad, mount);
    const double t_s = beam.t_log_s + mount.time_offset_s;  // on the navigation clock
    input.beams.push_back(
        {t_s, readings_of(t_s, segment_profile(beam.intensity, setup.bin_m, config), bearing, mount,
                          config)});
  }
  return input;
}

SonarInput from_detections(const DatasetFiles& files, const io::SonarSetup& setup,
                           const SonarMount& mount, const SegmentationConfig& config) {
  if (!files.beam_times) {
    io::fail_file(files.dir, "detections need *_IS_timestamps.log for the beam times");
  }
  const std::vector<io::BeamTimeRecord> times = io::read_beam_times_log(*files.beam_times);
  return readings_from_detections(files, times, io::read_detections(*files.detections), setup,
                                  mount, config);
}

}  // namespace

SonarInput readings_from_detections(const DatasetFiles& files,
                                    const std::vector<io::BeamTimeRecord>& times,
                                    const std::vector<io::DetectionRecord>& rows,
                                    const io::SonarSetup& setup, const SonarMount& mount,
                                    const SegmentationConfig& config) {
  SonarInput input;
  input.source = "detections";
  // Beam times on the navigation clock.
  for (const io::BeamTimeRecord& t : times) {
    input.beams.push_back({t.t_log_s + mount.time_offset_s, {}});
  }
  std::size_t i = 0;
  while (i < rows.size()) {
    const io::DetectionRecord& first = rows[i];
    if (first.beam_row < 0 || static_cast<std::size_t>(first.beam_row) >= times.size()) {
      io::fail_file(*files.detections, "beam_row " + std::to_string(first.beam_row) +
                                           " is not a row of " + *files.beam_times);
    }
    std::vector<double> ranges_m;
    for (; i < rows.size() && rows[i].beam_row == first.beam_row; ++i) {
      ranges_m.push_back(rows[i].range_m);
    }
    BeamReadings& beam = input.beams[static_cast<std::size_t>(first.beam_row)];
    beam.readings = readings_of(beam.t_s, segment_detections(ranges_m, setup.bin_m, config),
                                sonar_bearing_in_vehicle(first.angle_rad, mount), mount, config);
  }
  input.beams_per_revolution = io::steps_per_revolution(setup);
  return input;
}

SonarInput load_sonar_readings(const DatasetFiles& files, const Calibration& calibration,
                               const SegmentationConfig& segmentation) {
  const io::SonarSetup setup = files.setup ? io::read_setup_log(*files.setup) : io::SonarSetup{};
  SonarInput input;
  const bool raw = files.is_log && segmentation.source != SonarSource::kDetections;
  const bool detections = files.detections && segmentation.source != SonarSource::kRaw;
  if (raw) {
    input = from_is_log(io::read_is_log(*files.is_log), setup, calibration.sonar, segmentation);
  } else if (detections) {
    input = from_detections(files, setup, calibration.sonar, segmentation);
  } else if (segmentation.source == SonarSource::kRaw) {
    io::fail_file(files.dir, "no raw sonar data (*_IS.log), and segmentation.source is raw");
  } else if (segmentation.source == SonarSource::kDetections) {
    io::fail_file(files.dir,
                  "no sonar detections (*_detections.csv[.gz]), and segmentation.source is "
                  "detections");
  } else {
    io::fail_file(files.dir, "no sonar data (*_IS.log or *_detections.csv[.gz])");
  }
  input.beams_per_revolution = io::steps_per_revolution(setup);
  return input;
}

SonarInput load_sonar_readings(const RunInputs& in) {
  if (!in.records) return load_sonar_readings(in.files, in.calibration, in.config.segmentation);
  const DatasetRecords& r = *in.records;
  const SegmentationConfig& segmentation = in.config.segmentation;
  SonarInput input;
  if (!r.is_log.empty() && segmentation.source != SonarSource::kDetections) {
    input = from_is_log(r.is_log, r.setup, in.calibration.sonar, segmentation);
  } else if (r.has_detections && !r.beam_times.empty() &&
             segmentation.source != SonarSource::kRaw) {
    DatasetFiles names;
    names.dir = r.name;
    names.detections = r.name + " detections";
    names.beam_times = r.name + " beam times";
    input = readings_from_detections(names, r.beam_times, r.detections, r.setup,
                                     in.calibration.sonar, segmentation);
  } else {
    io::fail_file(r.name,
                  "no sonar data for segmentation.source " +
                      std::string(segmentation.source == SonarSource::kRaw          ? "raw"
                                  : segmentation.source == SonarSource::kDetections ? "detections"
                                                                                    : "auto"));
  }
  input.beams_per_revolution = io::steps_per_revolution(r.setup);
  return input;
}

bool has_sonar_data(const RunInputs& in) {
  if (in.records) return !in.records->is_log.empty() || in.records->has_detections;
  return in.files.is_log || in.files.detections;
}

}  // namespace msislab::dataset
