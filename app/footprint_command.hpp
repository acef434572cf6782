// `msislab footprint DATASET_DIR... --out SLAM.yaml [--config BASE.yaml] [grid options]`: the
// beam's footprint measured on simulated datasets against their truth (eval/
// footprint_calibration.hpp), written as a SLAM config: BASE's text as it is, then the
// `footprint` section with the table (docs/scan_matching.md, "The beam's footprint";
// docs/formats.md). Runs given that config correct every scan's wall points with it.
#pragma once

#include <string>
#include <vector>

namespace msislab::app {

struct FootprintOptions {
  std::vector<std::string> dataset_dirs;  ///< simulated: each with truth/beams.csv
  std::string out_path;                   ///< the SLAM config written
  std::string config_path;                ///< the base config (empty: the defaults)
  double range_step_m = 5.0;              ///< the grid's range nodes: step, 2 step, ... max
  double max_range_m = 50.0;
  double incidence_step_deg = 15.0;  ///< incidence nodes: 0, step, ... below 90
  int min_samples = 20;
  double max_offset_m = 5.0;
};

struct FootprintSummary {
  std::size_t datasets = 0;
  std::size_t readings = 0;  ///< readings of the scans built
  std::size_t samples = 0;   ///< of those on a line, with an axis hit in the truth
  std::size_t left_out = 0;  ///< samples beyond max_offset_m
  std::size_t cells = 0;     ///< cells of the grid
  std::size_t cells_with_figure = 0;
  /// The readings' bearing errors against truth (eval/footprint_calibration's
  /// bearing_offsets_rad): how many, their root mean square, and that over the datasets'
  /// horizontal beamwidth (NaN when the datasets' scenarios differ in it or have none).
  std::size_t bearing_samples = 0;
  double bearing_rms_rad = 0.0;
  double bearing_rms_over_beamwidth = 0.0;
};

/// Throws io::InputError on bad input: a dataset without truth/beams.csv, a base config that
/// already has a footprint section, a grid option out of range, an output that is not msislab's.
FootprintSummary measure_footprint_command(const FootprintOptions& options);

}  // namespace msislab::app
