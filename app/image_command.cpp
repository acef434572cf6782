#include "app/image_command.hpp"

#include <CLI/CLI.hpp>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "dataset/sonar_revolution.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "plot/acoustic_image.hpp"

namespace msislab::app {

void draw_image(const ImageOptions& options) {
  if (options.revolution < 0) {
    throw io::InputError("--revolution " + std::to_string(options.revolution) +
                         ": must be 0 or more");
  }
  io::check_output_file({options.out_path, "image", "image", {options.dataset_dir}, false},
                        io::png_written_by_msislab);
  const dataset::SonarRevolution revolution =
      options.keyframe > 0
          ? dataset::read_detected_revolution(options.dataset_dir, options.keyframe)
          : dataset::read_revolution(options.dataset_dir, options.revolution);
  plot::write_acoustic_image(options.out_path, revolution.beams, revolution.setup, revolution.mount,
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
