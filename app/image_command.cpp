#include "app/image_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "io/acoustic_image.hpp"
#include "io/dataset.hpp"
#include "io/detections.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"

namespace msislab::app {

namespace {
/// What drawing any revolution of the dataset needs: its setup and the sonar's mount, no beams.
SonarRevolution drawing_frame(const std::string& dataset_dir, const io::DatasetFiles& files) {
  SonarRevolution out;
  out.dataset_dir = dataset_dir;
  out.setup = files.setup ? io::read_setup_log(*files.setup) : io::SonarSetup{};
  out.mount = io::load_calibration(files).sonar;
  return out;
}
}  // namespace

SonarRevolution read_revolution(const std::string& dataset_dir, int revolution) {
  const io::DatasetFiles files = io::find_dataset_files(dataset_dir);
  if (!files.is_log) {
    io::fail_file(dataset_dir, "no *_IS.log (raw sonar beams) to draw an image from");
  }
  SonarRevolution out = drawing_frame(dataset_dir, files);
  const std::vector<io::SonarBeamRecord> beams = io::read_is_log(*files.is_log);
  const auto steps = static_cast<std::size_t>(std::lround(2.0 * M_PI / out.setup.step_rad));
  const std::size_t revolutions = (beams.size() + steps - 1) / steps;
  out.index = revolution >= 0 ? revolution : static_cast<int>(revolutions / 2);
  const std::size_t first = static_cast<std::size_t>(out.index) * steps;
  if (first >= beams.size()) {
    throw io::InputError("--revolution " + std::to_string(revolution) + ": the log has " +
                         std::to_string(revolutions) + " revolutions");
  }
  out.beams.assign(beams.begin() + static_cast<long>(first),
                   beams.begin() + static_cast<long>(std::min(beams.size(), first + steps)));
  return out;
}

SonarRevolution read_detected_revolution(const std::string& dataset_dir, int keyframe) {
  const io::DatasetFiles files = io::find_dataset_files(dataset_dir);
  if (!files.detections) {
    io::fail_file(dataset_dir, "no *_detections.csv[.gz] to draw --keyframe from");
  }
  SonarRevolution out = drawing_frame(dataset_dir, files);
  out.index = keyframe;
  const auto bins = static_cast<std::size_t>(std::lround(out.setup.range_m / out.setup.bin_m));
  std::int32_t keyframes = 0;
  std::int64_t beam_row = -1;
  for (const io::DetectionRecord& row : io::read_detections(*files.detections)) {
    keyframes = std::max(keyframes, row.keyframe);
    if (row.keyframe != keyframe) continue;
    if (row.beam_row != beam_row) {
      beam_row = row.beam_row;
      out.beams.push_back({row.t_log_s, static_cast<double>(row.sensor_time_ms), row.angle_rad,
                           std::vector<std::uint8_t>(bins, 0)});
    }
    const long bin = std::lround(row.range_m / out.setup.bin_m) - 1;
    if (bin >= 0 && bin < static_cast<long>(bins)) out.beams.back().intensity[bin] = 255;
  }
  if (out.beams.empty()) {
    throw io::InputError("--keyframe " + std::to_string(keyframe) + ": " + *files.detections +
                         " has keyframes 1.." + std::to_string(keyframes));
  }
  return out;
}

void draw_image(const ImageOptions& options) {
  if (options.revolution < 0) {
    throw io::InputError("--revolution " + std::to_string(options.revolution) +
                         ": must be 0 or more");
  }
  io::check_output_file({options.out_path, "image", "image", {options.dataset_dir}, false},
                        io::png_written_by_msislab);
  const SonarRevolution revolution =
      options.keyframe > 0 ? read_detected_revolution(options.dataset_dir, options.keyframe)
                           : read_revolution(options.dataset_dir, options.revolution);
  io::write_acoustic_image(options.out_path, revolution.beams, revolution.setup, revolution.mount,
                           options.size_px);
}

void add_image_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<ImageOptions>();
  CLI::App* image = app.add_subcommand(
      "image", "Draw one sonar revolution of a dataset's *_IS.log as an acoustic image (PNG)");
  image->add_option("DATASET_DIR", options->dataset_dir, "Dataset directory with a *_IS.log")
      ->required();
  image->add_option("--out,-o", options->out_path, "PNG file to write")->required();
  image->add_option("--revolution,-r", options->revolution, "0-based revolution to draw")
      ->check(CLI::NonNegativeNumber);
  image
      ->add_option("--keyframe,-k", options->keyframe,
                   "Draw keyframe K (1-based) of *_detections.csv[.gz] instead, detected bins at "
                   "full intensity (the real St. Pere data have only detections)")
      ->check(CLI::PositiveNumber);
  image->add_option("--size", options->size_px, "Image width and height in pixels")
      ->check(CLI::Range(100, 4000));
  image->callback([options] {
    draw_image(*options);
    std::cout << "wrote " << options->out_path << std::endl;
  });
}

}  // namespace msislab::app
