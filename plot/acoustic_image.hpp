// Acoustic image of one sonar revolution: the polar echo profiles drawn as a Cartesian fan in the
// vehicle frame (forward up, port left) with range rings, written as PNG through OpenCV; alone, or
// as a figure with a title and a colour bar.
#pragma once

#include <string>
#include <vector>

#include "geometry/calibration.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::plot {

/// Draws `beams` (one revolution or less) with `size_px` x `size_px` pixels out to the setup's
/// range; each pixel takes the beam nearest in bearing and the bin nearest in range.
void write_acoustic_image(const std::string& path, const std::vector<io::SonarBeamRecord>& beams,
                          const io::SonarSetup& setup, const SonarMount& mount, int size_px);

/// The same fan as a report figure of width_px x height_px on white: a title and a caption above,
/// the echo intensity colour bar beside it.
void write_acoustic_figure(const std::string& path, const std::vector<io::SonarBeamRecord>& beams,
                           const io::SonarSetup& setup, const SonarMount& mount,
                           const std::string& title, int width_px, int height_px);

}  // namespace msislab::plot
