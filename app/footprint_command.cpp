#include "app/footprint_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli.hpp"
#include "app/run_method.hpp"
#include "dataset/sonar_readings.hpp"
#include "dataset/truth.hpp"
#include "eval/footprint_calibration.hpp"
#include "io/atomic_file.hpp"
#include "io/beam_truth.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "settings/config_yaml.hpp"
#include "settings/footprint_yaml.hpp"
#include "settings/scenario_yaml.hpp"
#include "slam/scan_slam_pipeline.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab::app {

namespace {

constexpr const char* kSignature =
    "# A SLAM config with the beam's footprint, written by msislab footprint";

bool written_by_footprint(const std::string& path) {
  std::ifstream in(path);
  std::string first;
  return std::getline(in, first) && first == kSignature;
}

FootprintGrid grid_of(const FootprintOptions& o) {
  if (!(o.range_step_m > 0.0) || !(o.max_range_m >= o.range_step_m)) {
    io::fail_file("--range-step/--max-range", "need 0 < range step <= max range");
  }
  if (!(o.incidence_step_deg > 0.0 && o.incidence_step_deg < 90.0)) {
    io::fail_file("--incidence-step", "must lie in (0, 90) deg");
  }
  if (o.min_samples < 2) io::fail_file("--min-samples", "must be at least 2");
  if (!(o.max_offset_m > 0.0)) io::fail_file("--max-offset", "must be above 0");
  FootprintGrid grid;
  for (int i = 1; i * o.range_step_m <= o.max_range_m + 1e-9; ++i) {
    grid.ranges_m.push_back(i * o.range_step_m);
  }
  for (int j = 0; j * o.incidence_step_deg < 90.0 - 1e-9; ++j) {
    grid.incidences_rad.push_back(j * o.incidence_step_deg * M_PI / 180.0);
  }
  grid.min_samples = o.min_samples;
  grid.max_abs_offset_m = o.max_offset_m;
  return grid;
}

/// The samples of one dataset: its scans built with the base config; its readings' bearing errors
/// appended to `bearings`.
std::vector<FootprintSample> dataset_samples(const std::string& dir, const std::string& config,
                                             const LineNormalConfig& line, std::size_t& readings,
                                             std::vector<double>& bearings) {
  const dataset::RunInputs in = dataset::load_run_inputs(dir, config);
  if (!in.files.truth_beams) {
    io::fail_file(dir, "no truth/beams.csv (footprint needs simulated datasets)");
  }
  // The base has no footprint section (refused before), so these scans are as read.
  const dataset::SonarInput sonar =
      dataset::load_sonar_readings(in.files, in.calibration, in.config.segmentation);
  const std::vector<PlacedScan> scans =
      build_placed_scans(in.navigation, sonar.beams, in.config, scan_slam_setup(in, sonar));
  for (const PlacedScan& s : scans) readings += s.scan.points.size();
  std::vector<AxisTruth> beams;
  for (const io::BeamTruthRow& row : io::read_beam_truth(*in.files.truth_beams)) {
    beams.push_back(
        {row.t_s, row.first_hit_range_m, row.strongest_range_m, row.strongest_bearing_offset_rad});
  }
  const std::vector<double> b = bearing_offsets_rad(scans, beams);
  bearings.insert(bearings.end(), b.begin(), b.end());
  return footprint_samples(scans, beams, line);
}

/// The horizontal beamwidth of the scenario a dataset was simulated from (its scenario.yaml), deg;
/// NaN without one.
double dataset_beamwidth_deg(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "scenario.yaml").string();
  if (!std::filesystem::exists(path)) return std::nan("");
  return settings::read_scenario(path).sonar.horizontal_beamwidth_deg;
}

/// The comment above the written table: the datasets, the samples, and the bearing errors.
std::string provenance_comment(const FootprintOptions& options, const FootprintGrid& grid,
                               const FootprintSummary& summary, const FootprintEstimate& estimate) {
  std::string comment = "measured on";
  for (const std::string& dir : options.dataset_dirs) comment += "\n  " + dir;
  std::ostringstream from;
  from << "\nfrom " << summary.samples << " readings on lines (" << summary.left_out
       << " more than " << grid.max_abs_offset_m << " m off their axis left out)";
  from << "\nreadings' bearing error against truth (the strongest echo's source off the axis): ";
  if (summary.bearing_samples == 0) {
    from << "none (no bearing in the truth)";
  } else {
    from << summary.bearing_rms_rad * 180.0 / M_PI << " deg rms over " << summary.bearing_samples
         << " readings";
  }
  if (summary.bearing_samples > 0 && std::isfinite(summary.bearing_rms_over_beamwidth)) {
    from << ", " << summary.bearing_rms_over_beamwidth << " of the "
         << summary.bearing_rms_rad / summary.bearing_rms_over_beamwidth * 180.0 / M_PI
         << " deg beamwidth";
  }
  from << "\nthe wall readings' bearing toward their wall's normal (mean and rms, deg) by "
          "incidence:";
  for (std::size_t j = 0; j < grid.incidences_rad.size(); ++j) {
    from << "\n  " << grid.incidences_rad[j] * 180.0 / M_PI
         << " deg: " << estimate.bearing_toward_normal_mean_rad[j] * 180.0 / M_PI << ", "
         << estimate.bearing_toward_normal_rms_rad[j] * 180.0 / M_PI << " ("
         << estimate.bearing_samples[j] << ")";
  }
  comment += from.str();
  return comment;
}

}  // namespace

FootprintSummary measure_footprint_command(const FootprintOptions& options) {
  std::vector<std::string> inputs = options.dataset_dirs;
  if (!options.config_path.empty()) inputs.push_back(options.config_path);
  io::check_output_file({options.out_path, "SLAM config", "footprint", inputs, false},
                        written_by_footprint);
  const FootprintGrid grid = grid_of(options);
  const SlamConfig base =
      options.config_path.empty() ? SlamConfig{} : settings::read_slam_config(options.config_path);
  std::string base_text;
  if (!options.config_path.empty()) {
    base_text = io::read_whole_file(options.config_path);
    if (settings::has_footprint_section(options.config_path)) {
      io::fail_file(options.config_path,
                    "has a footprint section: remove it (the section is written whole, its line "
                    "keys at their defaults)");
    }
  }
  FootprintSummary summary;
  std::vector<FootprintSample> samples;
  std::vector<double> bearings;
  double beamwidth_deg = 0.0;  // the datasets' one beamwidth, NaN when they differ or have none
  for (const std::string& dir : options.dataset_dirs) {
    const std::vector<FootprintSample> s =
        dataset_samples(dir, options.config_path, base.footprint.line, summary.readings, bearings);
    samples.insert(samples.end(), s.begin(), s.end());
    const double beam_deg = dataset_beamwidth_deg(dir);
    beamwidth_deg = summary.datasets++ == 0 || beam_deg == beamwidth_deg ? beam_deg : std::nan("");
  }
  summary.bearing_samples = bearings.size();
  summary.bearing_rms_rad = rms(bearings);
  summary.bearing_rms_over_beamwidth = summary.bearing_rms_rad / (beamwidth_deg * M_PI / 180.0);
  const FootprintEstimate estimate = estimate_footprint(samples, grid);
  summary.samples = samples.size();
  summary.left_out = estimate.left_out;
  summary.cells = estimate.samples.size();
  for (const int n : estimate.samples) summary.cells_with_figure += n >= grid.min_samples;
  if (summary.cells_with_figure == 0) {
    io::fail_file(
        options.dataset_dirs.front(),
        "no cell of the grid has " + std::to_string(grid.min_samples) + " samples (" +
            std::to_string(summary.samples) +
            " readings on lines matched a beam's truth): simulate more, or widen the grid");
  }
  const std::string comment = provenance_comment(options, grid, summary, estimate);
  std::string text = std::string(kSignature) + "\n";
  if (!options.config_path.empty()) {
    text += "# Its base, " + options.config_path + ", as it is:\n" + base_text;
    if (!base_text.empty() && base_text.back() != '\n') text += '\n';
  }
  text +=
      settings::footprint_section_yaml(estimate, grid.min_samples, base.footprint.line, comment);
  // What is written must read back as the config it stands for.
  settings::read_slam_config_text(text, options.out_path);
  io::write_text_atomically(options.out_path, text);
  return summary;
}

void add_footprint_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<FootprintOptions>();
  CLI::App* cmd = app.add_subcommand(
      "footprint",
      "Measure the beam's footprint (range reported less range on the beam's axis, by range and "
      "incidence) on simulated datasets against their truth; writes a SLAM config that corrects "
      "scans with it");
  cmd->add_option("DATASET_DIR", options->dataset_dirs,
                  "Simulated dataset directories (with truth/beams.csv)")
      ->required();
  cmd->add_option("--out,-o", options->out_path, "SLAM config YAML to write")->required();
  cmd->add_option(
      "--config,-c", options->config_path,
      "Base SLAM config: its front end builds the scans, and its text heads the output");
  cmd->add_option("--range-step", options->range_step_m, "Range nodes' step, m (default 5)");
  cmd->add_option("--max-range", options->max_range_m, "Last range node, m (default 50)");
  cmd->add_option("--incidence-step", options->incidence_step_deg,
                  "Incidence nodes' step from 0, deg (default 15)");
  cmd->add_option("--min-samples", options->min_samples,
                  "Fewer samples in a cell: no figure there (default 20)");
  cmd->add_option("--max-offset", options->max_offset_m,
                  "Readings farther than this from their axis's first hit are left out, m "
                  "(default 5)");
  cmd->callback([options] {
    const FootprintSummary s = measure_footprint_command(*options);
    std::cout << "wrote " << options->out_path << ": " << s.cells_with_figure << " of " << s.cells
              << " cells from " << s.samples << " readings on lines of " << s.readings << " in "
              << s.datasets << " datasets (" << s.left_out << " left out); ";
    if (s.bearing_samples == 0) {
      std::cout << "no bearing error (no reading lies near its beam's strongest echo with a "
                   "bearing in the truth: datasets simulated before truth/beams.csv had one?)\n";
      return;
    }
    std::cout << "bearing error " << s.bearing_rms_rad * 180.0 / M_PI << " deg rms over "
              << s.bearing_samples << " readings";
    if (std::isfinite(s.bearing_rms_over_beamwidth)) {
      std::cout << " (" << s.bearing_rms_over_beamwidth << " of the beamwidth)";
    }
    std::cout << "\n";
  });
}

}  // namespace msislab::app
