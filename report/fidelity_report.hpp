// The simulator against the real sonar, statistic by statistic (docs/fidelity.md): both datasets'
// detections read and reduced by the same code, the table of their values (report/fidelity_table),
// and the page and JSON `msislab fidelity` writes of it (fidelity.md, fidelity.json). The command,
// app/fidelity_command, checks the output folder, draws the figures and writes the files.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dataset/dataset.hpp"
#include "dataset/detected_beams.hpp"
#include "geometry/calibration.hpp"
#include "io/json.hpp"
#include "io/stpere_logs.hpp"
#include "report/fidelity_table.hpp"

namespace msislab::report {

struct FidelityOptions {
  std::string real_dir;
  std::string sim_dir;
  std::string out_dir;                          ///< empty: print the table only
  std::optional<std::int32_t> revolution_real;  ///< keyframe drawn; default: the middle one
  std::optional<std::int32_t> revolution_sim;   ///< default: nearest in time to the real one
  bool force = false;                           ///< replace a folder msislab did not write
};

/// One dataset's detections, read, checked and reduced to statistics.
struct FidelitySide {
  std::string dir;
  dataset::DatasetFiles files;
  io::SonarSetup setup;
  Calibration calibration;
  std::size_t beam_times = 0;  ///< rows of *_IS_timestamps.log
  std::vector<DetectedBeam> beams;
  SonarStatistics stats;
  std::int32_t revolution = 0;   ///< the keyframe drawn in revolution.png
  std::vector<double> beam_t_s;  ///< log time of every row of *_IS_timestamps.log
};

struct FidelityReport {
  FidelityOptions options;
  FidelitySide real;
  FidelitySide sim;
  FidelityTable table;      ///< the sonar rows, then the navigation rows
  bool navigation = false;  ///< both datasets have DVL and MTi logs: navigation rows present
};

/// Reads both datasets (*_detections.csv[.gz], *_IS_timestamps.log, *_SETUP.log,
/// calibration.yaml) and computes the table; needs no display. Throws io::InputError naming the
/// file for a missing directory or file, malformed detections or beam times, setups that differ
/// or a revolution not in the file.
FidelityReport compare_datasets(const FidelityOptions& options);

/// `msislab fidelity ...` with the options as given: what the page says made it.
std::string fidelity_command_line(const FidelityOptions& options);

/// fidelity.md: the datasets, the table, how each statistic is computed, the figures.
std::string fidelity_page(const FidelityReport& report);

/// fidelity.json: the command, the datasets and every row.
io::Json fidelity_json(const FidelityReport& report);
/// How fidelity.json is laid out: one member per line, and one row per line.
inline const io::JsonLayout kFidelityJsonLayout{1, {"rows"}};

}  // namespace msislab::report
