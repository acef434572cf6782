// Both datasets of `msislab fidelity` read, checked against each other and reduced to the table.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "dataset/navigation_data.hpp"
#include "dataset/sonar_readings.hpp"
#include "io/detections.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "report/fidelity_report.hpp"

namespace msislab::report {

namespace {

std::vector<double> times_s(const std::vector<io::BeamTimeRecord>& times) {
  std::vector<double> t_s;
  t_s.reserve(times.size());
  for (const io::BeamTimeRecord& t : times) t_s.push_back(t.t_log_s);
  return t_s;
}

/// The requested keyframe, or the middle one; it must lie within the file's keyframes.
std::int32_t pick_revolution(const FidelitySide& side, std::optional<std::int32_t> requested,
                             const std::string& option) {
  const std::int32_t first = side.beams.front().keyframe, last = side.beams.back().keyframe;
  if (!requested) return first + (last - first) / 2;
  if (*requested < first || *requested > last) {
    io::fail_file(*side.files.detections, option + " " + std::to_string(*requested) +
                                              ": the keyframes here are " + std::to_string(first) +
                                              ".." + std::to_string(last));
  }
  return *requested;
}

/// The dataset's files, sonar setup and calibration.
FidelitySide open_side(const std::string& dir) {
  FidelitySide side;
  side.dir = dir;
  side.files = dataset::find_dataset_files(dir);
  if (!side.files.detections) {
    io::fail_file(dir, "no *_detections.csv[.gz] file (fidelity compares detected bins)");
  }
  if (!side.files.beam_times) {
    io::fail_file(dir, "no *_IS_timestamps.log file (the detections need the beam times)");
  }
  side.setup = side.files.setup ? io::read_setup_log(*side.files.setup) : io::SonarSetup{};
  side.calibration = dataset::load_calibration(side.files);
  return side;
}

/// The detections and beam times, checked and reduced to statistics.
void load_detections(FidelitySide& side, std::optional<std::int32_t> revolution,
                     const std::string& revolution_option) {
  const dataset::DatasetFiles& files = side.files;
  const std::vector<io::BeamTimeRecord> times = io::read_beam_times_log(*files.beam_times);
  const std::vector<io::DetectionRecord> rows = io::read_detections(*files.detections);
  side.beam_times = times.size();
  const int per_revolution = io::steps_per_revolution(side.setup);
  side.beams = dataset::group_detections(rows, *files.detections, times.size(), per_revolution,
                                         side.setup.range_m);
  side.stats = sonar_statistics(side.beams, times_s(times), per_revolution, side.setup.bin_m,
                                side.setup.step_rad);
  const dataset::SonarInput readings = dataset::readings_from_detections(
      files, times, rows, side.setup, side.calibration.sonar, SegmentationConfig{});
  side.stats.readings_per_revolution = readings_per_keyframe(side.beams, readings.beams);
  side.revolution = pick_revolution(side, revolution, revolution_option);
  side.beam_t_s = times_s(times);
}

/// Mean log time of each keyframe's detected beams, in one pass.
std::map<std::int32_t, double> keyframe_times_s(const FidelitySide& side) {
  std::map<std::int32_t, std::pair<double, int>> sums;
  for (const DetectedBeam& b : side.beams) {
    auto& [sum_s, n] = sums[b.keyframe];
    sum_s += side.beam_t_s[static_cast<std::size_t>(b.beam_row)];
    ++n;
  }
  std::map<std::int32_t, double> times_s;
  for (const auto& [keyframe, sum] : sums) times_s[keyframe] = sum.first / sum.second;
  return times_s;
}

/// A simulated run timed to the real one (its log times overlap the real keyframe drawn): the
/// simulated keyframe nearest in time, so the figure shows both at the same place.
void align_simulated_revolution(const FidelitySide& real, FidelitySide& sim) {
  const std::map<std::int32_t, double> real_times_s = keyframe_times_s(real);
  const auto drawn = real_times_s.find(real.revolution);
  if (drawn == real_times_s.end() || sim.beam_t_s.empty() || drawn->second < sim.beam_t_s.front() ||
      drawn->second > sim.beam_t_s.back()) {
    return;
  }
  double best_s = std::numeric_limits<double>::infinity();
  for (const auto& [keyframe, t_s] : keyframe_times_s(sim)) {
    if (std::abs(t_s - drawn->second) < best_s) {
      best_s = std::abs(t_s - drawn->second);
      sim.revolution = keyframe;
    }
  }
}

std::string describe(const io::SonarSetup& s) {
  return "range " + io::format_number(s.range_m) + " m, bin " + io::format_number(s.bin_m) +
         " m, " + std::to_string(io::steps_per_revolution(s)) + " steps per revolution";
}

/// Equal to the digits a setup log gives (6 significant ones).
bool same(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(std::abs(a), 1e-3); }

void check_same_setup(const FidelitySide& real, const FidelitySide& sim) {
  const io::SonarSetup& a = real.setup;
  const io::SonarSetup& b = sim.setup;
  if (same(a.range_m, b.range_m) && same(a.bin_m, b.bin_m) &&
      io::steps_per_revolution(a) == io::steps_per_revolution(b)) {
    return;
  }
  const std::string real_name = real.files.setup.value_or(real.dir + " (no *_SETUP.log: default)");
  io::fail_file(sim.files.setup.value_or(sim.dir + " (no *_SETUP.log: default setup)"),
                "sonar setup (" + describe(b) + ") differs from " + real_name + " (" + describe(a) +
                    "): the statistics would not compare");
}

bool has_navigation_logs(const std::string& dir) {
  const dataset::DatasetFiles files = dataset::find_dataset_files(dir);
  return files.dvl && files.mti;
}

/// The navigation rows: noise from sample differences, dropouts and dead-reckoning drift per
/// 100 m against the truth (docs/simulator.md, "Navigation noise from the real logs").
void append_navigation_rows(const std::string& real_dir, const std::string& sim_dir,
                            FidelityTable& table) {
  const NavigationStatistics real = navigation_statistics(dataset::load_navigation_data(real_dir));
  const NavigationStatistics sim = navigation_statistics(dataset::load_navigation_data(sim_dir));
  const std::string section = "Navigation";
  table.push_back({section, "dvl_noise_surge_mps", "DVL velocity noise, surge (sample differences)",
                   real.dvl.surge_mps.sigma_sd, sim.dvl.surge_mps.sigma_sd, std::nullopt, "m/s",
                   3});
  table.push_back({section, "dvl_noise_sway_mps", "DVL velocity noise, sway (sample differences)",
                   real.dvl.sway_mps.sigma_sd, sim.dvl.sway_mps.sigma_sd, std::nullopt, "m/s", 3});
  table.push_back({section, "dvl_noise_surge_mad_mps", "DVL velocity noise, surge (robust, MAD)",
                   real.dvl.surge_mps.sigma_mad, sim.dvl.surge_mps.sigma_mad, std::nullopt, "m/s",
                   3});
  table.push_back({section, "dvl_rate_hz", "DVL rate", real.dvl.rate_hz, sim.dvl.rate_hz,
                   std::nullopt, "Hz", 3});
  table.push_back({section, "dvl_dropout_percent", "DVL rows without bottom lock",
                   100.0 * real.dropouts.fraction, 100.0 * sim.dropouts.fraction, std::nullopt, "%",
                   2});
  table.push_back({section, "heading_noise_deg", "heading noise (second differences)",
                   real.heading.noise_deg.sigma_sd, sim.heading.noise_deg.sigma_sd, std::nullopt,
                   "deg", 3});
  table.push_back({section, "turn_per_revolution_deg",
                   "heading change over one revolution (13.8 s), median",
                   real.heading.turn_per_revolution_deg, sim.heading.turn_per_revolution_deg,
                   std::nullopt, "deg", 1});
  if (real.drift && sim.drift) {
    table.push_back({section, "drift_per_100m_mean_m",
                     "dead-reckoning drift per 100 m against the truth, mean", real.drift->mean_m,
                     sim.drift->mean_m, std::nullopt, "m", 2});
    table.push_back({section, "drift_per_100m_p90_m",
                     "dead-reckoning drift per 100 m against the truth, p90", real.drift->p90_m,
                     sim.drift->p90_m, std::nullopt, "m", 2});
  }
}
}  // namespace

FidelityReport compare_datasets(const FidelityOptions& options) {
  FidelityReport report;
  report.options = options;
  report.real = open_side(options.real_dir);
  report.sim = open_side(options.sim_dir);
  check_same_setup(report.real, report.sim);
  load_detections(report.real, options.revolution_real, "--revolution-real");
  load_detections(report.sim, options.revolution_sim, "--revolution-sim");
  if (!options.revolution_sim) align_simulated_revolution(report.real, report.sim);
  report.table = sonar_rows(report.real.stats, report.sim.stats, report.real.setup.range_m);
  // Datasets that carry the DVL and MTi logs are compared on their navigation too.
  report.navigation = has_navigation_logs(options.real_dir) && has_navigation_logs(options.sim_dir);
  if (report.navigation) append_navigation_rows(options.real_dir, options.sim_dir, report.table);
  return report;
}

}  // namespace msislab::report
