// The figures of `msislab fidelity` as plain plot::ChartSpec: the range histograms of the two
// datasets overlaid, and one revolution of detections from each side by side.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/detected_beams.hpp"
#include "geometry/calibration.hpp"
#include "plot/chart.hpp"

namespace msislab::report {

/// How a dataset appears in the figures.
struct FigureSide {
  std::string role;     ///< "Real" or "Simulated"
  std::string dataset;  ///< its folder's name
  const SonarStatistics* stats = nullptr;
  const std::vector<DetectedBeam>* beams = nullptr;
  SonarMount mount;
  std::int32_t keyframe = 0;  ///< the revolution drawn
};

/// Two panels: the first detected range of each beam, and every detected bin, as histograms of
/// 1 m bins normalised to percent of the sample per metre, real solid and simulated dashed.
std::vector<plot::ChartSpec> range_charts(const FigureSide& real, const FigureSide& sim,
                                          double max_range_m);

/// Two panels with the same axes: the detected bins and the first range of each beam of one
/// keyframe, each dataset in its vehicle frame (x forward, y port; no motion compensation), with
/// range rings every 10 m around the sonar head.
std::vector<plot::ChartSpec> revolution_charts(const FigureSide& real, const FigureSide& sim,
                                               double max_range_m);

}  // namespace msislab::report
