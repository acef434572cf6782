#include "app/image_command.hpp"

#include <cmath>

#include "io/acoustic_image.hpp"
#include "io/dataset.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::app {

void draw_image(const ImageOptions& options) {
  const io::DatasetFiles files = io::find_dataset_files(options.dataset_dir);
  if (!files.is_log) {
    io::fail_file(options.dataset_dir, "no *_IS.log (raw sonar beams) to draw an image from");
  }
  const io::SonarSetup setup = files.setup ? io::read_setup_log(*files.setup) : io::SonarSetup{};
  const Calibration calibration = io::load_calibration(files);
  const std::vector<io::SonarBeamRecord> beams = io::read_is_log(*files.is_log);
  const auto steps = static_cast<std::size_t>(std::lround(2.0 * M_PI / setup.step_rad));
  const std::size_t first = static_cast<std::size_t>(options.revolution) * steps;
  if (options.revolution < 0 || first >= beams.size()) {
    throw io::InputError("--revolution " + std::to_string(options.revolution) + ": the log has " +
                         std::to_string((beams.size() + steps - 1) / steps) + " revolutions");
  }
  const std::vector<io::SonarBeamRecord> revolution(
      beams.begin() + static_cast<long>(first),
      beams.begin() + static_cast<long>(std::min(beams.size(), first + steps)));
  io::write_acoustic_image(options.out_path, revolution, setup, calibration.sonar, options.size_px);
}

}  // namespace msislab::app
