#include "app/segment_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>

#include "app/cli.hpp"
#include "dataset/dataset.hpp"
#include "io/atomic_file.hpp"
#include "io/beam_truth.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::app {
namespace {

constexpr double kHitTolerance_m = 0.3;

const std::vector<SegmentationMethod>& all_methods() {
  static const std::vector<SegmentationMethod> methods = {SegmentationMethod::kMaxIntensity,
                                                          SegmentationMethod::kThresholdGroups,
                                                          SegmentationMethod::kSmoothedFirst};
  return methods;
}

std::vector<SegmentationMethod> requested_methods(const std::vector<std::string>& names) {
  std::vector<SegmentationMethod> methods;
  for (const std::string& name : names) {
    SegmentationMethod method{};
    if (name == "all") {
      methods.insert(methods.end(), all_methods().begin(), all_methods().end());
    } else if (parse_segmentation_method(name, method)) {
      methods.push_back(method);
    } else {
      throw io::InputError("--method '" + name +
                           "': unknown (known: max_intensity, threshold_groups, smoothed_first, "
                           "all)");
    }
  }
  return methods.empty() ? all_methods() : methods;
}

SegmentationConfig config_for(SegmentationMethod method, const SegmentOptions& options) {
  SegmentationConfig config;
  config.method = method;
  if (options.threshold) config.threshold = *options.threshold;
  if (options.min_range_m) config.min_range_m = *options.min_range_m;
  return config;
}

std::vector<SegmentationTruth> scoring_truth(const std::vector<io::BeamTruthRow>& rows) {
  std::vector<SegmentationTruth> truth;
  truth.reserve(rows.size());
  for (const io::BeamTruthRow& row : rows) {
    truth.push_back({row.first_hit_range_m, row.strongest_multipath});
  }
  return truth;
}

SegmentationScore score_method(const std::vector<io::SonarBeamRecord>& beams, double bin_m,
                               const SegmentationConfig& config,
                               const std::vector<SegmentationTruth>& truth) {
  std::vector<std::vector<double>> ranges_m;
  ranges_m.reserve(beams.size());
  for (const io::SonarBeamRecord& beam : beams) {
    ranges_m.push_back(segment_profile(beam.intensity, bin_m, config));
  }
  return score_segmentation(truth, ranges_m, kHitTolerance_m);
}

std::string number(double value, int decimals) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string percent(double value) { return std::isnan(value) ? "-" : number(100.0 * value, 1); }

}  // namespace

std::string segmentation_markdown(const std::vector<SegmentRow>& rows) {
  std::string text =
      "| method | threshold | min range (m) | hit % | miss % | wrong % | false detections % | "
      "hit %, strongest direct | hit %, strongest multipath | hit range RMS (m) |\n"
      "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SegmentRow& row : rows) {
    const SegmentationScore& s = row.score;
    text += "| " + to_string(row.config.method) + " | " + number(row.config.threshold, 0) + " | " +
            number(row.config.min_range_m, 2) + " | " + percent(s.hit_fraction) + " | " +
            percent(s.miss_fraction) + " | " + percent(s.wrong_fraction) + " | " +
            percent(s.false_detection_fraction) + " | " + percent(s.hit_fraction_direct) + " | " +
            percent(s.hit_fraction_multipath) + " | " + number(s.hit_range_rms_m, 3) + " |\n";
  }
  if (rows.empty()) return text;
  const SegmentationScore& s = rows.front().score;
  text += "\n" + std::to_string(s.beams) + " beams, " + std::to_string(s.beams_with_hit) +
          " with a first hit on the axis (" + std::to_string(s.beams_multipath) +
          " of them with a multipath strongest echo). Hit: a reading within 0.3 m of the first "
          "hit; miss: no reading; wrong: readings, none within 0.3 m (these three over beams "
          "with a first hit). False detections: readings off the first hit or on beams without "
          "one, over all readings.\n";
  return text;
}

SegmentReport segment(const SegmentOptions& options) {
  const std::vector<SegmentationMethod> methods = requested_methods(options.methods);
  if (!options.out_path.empty()) {
    io::check_output_file({options.out_path, "page", "segment", {options.dataset_dir}, false},
                          io::page_written_by_msislab);
  }
  const dataset::DatasetFiles files = dataset::find_dataset_files(options.dataset_dir);
  if (!files.is_log) io::fail_file(options.dataset_dir, "no *_IS.log (raw sonar beams) to segment");
  if (!files.truth_beams) {
    io::fail_file(options.dataset_dir, "no truth/beams.csv (segment needs a simulated dataset)");
  }
  const io::SonarSetup setup = files.setup ? io::read_setup_log(*files.setup) : io::SonarSetup{};
  const std::vector<io::SonarBeamRecord> beams = io::read_is_log(*files.is_log);
  const std::vector<SegmentationTruth> truth =
      scoring_truth(io::read_beam_truth(*files.truth_beams));
  if (truth.size() != beams.size()) {
    io::fail_file(*files.truth_beams, std::to_string(truth.size()) + " beams, but " +
                                          *files.is_log + " has " + std::to_string(beams.size()));
  }
  SegmentReport report;
  for (const SegmentationMethod method : methods) {
    const SegmentationConfig config = config_for(method, options);
    report.rows.push_back({config, score_method(beams, setup.bin_m, config, truth)});
  }
  report.markdown = segmentation_markdown(report.rows);
  if (!options.out_path.empty()) {
    io::write_file_atomically(options.out_path, [&](std::ostream& out) {
      out << io::page_signature("segment") << report.markdown;
    });
  }
  return report;
}

void add_segment_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* command = app.add_subcommand(
      "segment",
      "Score beam segmentation methods on a simulated dataset against its truth/beams.csv");
  command
      ->add_option("DATASET_DIR", options->dataset_dir,
                   "Simulated dataset directory (*_IS.log, truth/beams.csv)")
      ->required();
  command->add_option("--method,-m", options->methods,
                      "Methods: max_intensity, threshold_groups, smoothed_first or all (default)");
  command
      ->add_option("--threshold", options->threshold,
                   "Intensity threshold 0..255 (default: the SegmentationConfig default)")
      ->check(CLI::Range(0.0, 255.0));
  command
      ->add_option("--min-range", options->min_range_m,
                   "Minimum range in m (default: the SegmentationConfig default)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--out,-o", options->out_path, "Also write the Markdown table to this file");
  command->callback([options] { std::cout << segment(*options).markdown << std::flush; });
}

}  // namespace msislab::app
