// Acoustic image of one sonar revolution: the polar echo profiles drawn as a Cartesian fan in the
// vehicle frame (forward up, port left) with range rings, written as PNG through OpenCV.
#pragma once

#include <string>
#include <vector>

#include "io/stpere_logs.hpp"
#include "slam/calibration.hpp"

namespace msislab::io {

/// Draws `beams` (one revolution or less) with `size_px` x `size_px` pixels out to the setup's
/// range; each pixel takes the beam nearest in bearing and the bin nearest in range.
void write_acoustic_image(const std::string& path, const std::vector<SonarBeamRecord>& beams,
                          const SonarSetup& setup, const SonarMount& mount, int size_px);

}  // namespace msislab::io
