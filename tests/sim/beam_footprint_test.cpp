// The beam's footprint on an oblique wall, measured on the simulator: the range each detector
// reports for a wall met at incidence psi (from its normal) by a beam of horizontal width b (the
// two-way -3 dB width), against the range on the beam's axis and the first-return limit
// d / cos(max(0, psi - delta)), d the perpendicular distance and delta = b / 2. What a SLAM's
// range model has to describe for each detector (docs/simulator.md, "The beam's footprint on an
// oblique wall"). The marina's vertical geometry: a wall from the seabed at 3.4 m to 1 m above
// the surface, the head 1.5 m down, the seabed of weak backscatter; the default sonar (its pulse,
// receiver, gain and speckle) with its beam set to each width; 50 pings per cell, seeded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "sim/detection_model.hpp"
#include "sim/msis.hpp"
#include "sim/random.hpp"
#include "slam/beam_segmentation.hpp"

namespace msislab::sim {
namespace {

constexpr double kAxisRange_m = 20.0;

/// The wall whose point on the +x axis lies kAxisRange_m away, turned so that the axis meets it
/// at incidence_deg from its normal, and the seabed.
TriangleMesh turned_wall(double incidence_deg) {
  const double phi = incidence_deg * M_PI / 180.0;
  const auto at = [&](double t, float z) {
    return Eigen::Vector3f(static_cast<float>(kAxisRange_m - t * std::sin(phi)),
                           static_cast<float>(t * std::cos(phi)), z);
  };
  TriangleMesh mesh;
  mesh.vertices_m = {at(-200, -3.4f),   at(200, -3.4f),      at(200, 1),
                     at(-200, 1),       {-100, -200, -3.4f}, {100, -200, -3.4f},
                     {100, 200, -3.4f}, {-100, 200, -3.4f}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
  mesh.material_ids = {0, 0, 1, 1};
  mesh.materials = {Material{"wall", 0.5f, 0.05f, 1.0f}, Material{"bottom", 0.003f, 0.3f, 2.0f}};
  mesh.group_names = {"wall", "bottom"};
  return mesh;
}

VehicleTrajectory still() {
  std::vector<VehicleState> samples;
  for (int k = 0; k <= 100; ++k) samples.push_back({0.01 * k, Pose2(0.0, 0.0, 0.0), 0.0, 0.0, 0.0});
  return VehicleTrajectory(samples);
}

/// A detector: the nearest range it reports on a profile, or none.
using Detector = std::function<std::vector<double>(const std::vector<std::uint8_t>&, double)>;

/// The mean over 50 pings of the nearest range the detector reports (NAN if it never does).
double mean_reported_m(double beam_deg, double incidence_deg, const Detector& detect) {
  SonarConfig sonar;
  sonar.mount.x_m = 0.0;
  sonar.mount.bearing_offset_rad = 0.0;
  sonar.mount.bearing_sign = 1.0;
  sonar.horizontal_beamwidth_deg = beam_deg;
  const Scene scene(turned_wall(incidence_deg), Material{"surface", 0.001f, 0.9f});
  const MsisModel model(scene, sonar, 1.5);
  Rng rng(7);
  double sum_m = 0.0;
  int found = 0;
  for (int ping = 0; ping < 50; ++ping) {
    const std::vector<double> r =
        detect(model.render({0, 0.0, 0.0}, still(), rng).intensity, sonar.bin_m);
    if (!r.empty()) sum_m += r.front(), ++found;
  }
  return found ? sum_m / found : NAN;
}

/// The leading edge: the first bin past 1 m at or above the front end's threshold (100).
std::vector<double> leading_edge(const std::vector<std::uint8_t>& intensity, double bin_m) {
  for (std::size_t j = 0; j < intensity.size(); ++j) {
    const double r_m = static_cast<double>(j + 1) * bin_m;
    if (r_m >= 1.0 && intensity[j] >= 100) return {r_m};
  }
  return {};
}

/// The front end's default on raw profiles: runs over the threshold, the strongest bin of each.
std::vector<double> strongest_of_run(const std::vector<std::uint8_t>& intensity, double bin_m) {
  return segment_profile(intensity, bin_m, SegmentationConfig{});
}

/// The detections path: the replica's detector (smoothing 23 bins) marks bins, the front end
/// reports each run's centre.
std::vector<double> run_centre(const std::vector<std::uint8_t>& intensity, double bin_m) {
  DetectionModelConfig detector;
  detector.smoothing_bins = 23;
  std::vector<double> ranges_m;
  for (const int j : detect_bins(intensity, bin_m, detector)) ranges_m.push_back((j + 1) * bin_m);
  return segment_detections(ranges_m, bin_m, SegmentationConfig{});
}

TEST(BeamFootprint, WhatEachDetectorReportsOnAnObliqueWall) {
  const double bin_m = SonarConfig{}.bin_m;
  const std::vector<double> beams_deg = {1.5, 3.0, 6.0, 9.0};
  const std::vector<double> incidences_deg = {0.0, 15.0, 30.0, 45.0, 60.0};
  std::printf(
      "axis range %.0f m; per beam and incidence: the first-return limit, then what the\n"
      "leading edge, the strongest bin of a run and a detections run's centre report\n",
      kAxisRange_m);
  std::vector<double> previous_edge_m(incidences_deg.size(), INFINITY);
  for (const double beam_deg : beams_deg) {
    double last_edge_m = INFINITY;
    for (std::size_t i = 0; i < incidences_deg.size(); ++i) {
      const double psi = incidences_deg[i] * M_PI / 180.0, delta = 0.5 * beam_deg * M_PI / 180.0;
      const double d_m = kAxisRange_m * std::cos(psi);
      const double limit_m = d_m / std::cos(std::max(0.0, psi - delta));
      const double edge_m = mean_reported_m(beam_deg, incidences_deg[i], leading_edge);
      const double strongest_m = mean_reported_m(beam_deg, incidences_deg[i], strongest_of_run);
      const double centre_m = mean_reported_m(beam_deg, incidences_deg[i], run_centre);
      // The half-width that puts the first return at the leading edge's range.
      const double edge_delta_deg =
          psi > 0.0 ? (psi - std::acos(d_m / edge_m)) * 180.0 / M_PI : 0.0;
      std::printf(
          "beam %.1f deg, psi %2.0f deg: limit %.2f m | leading edge %.2f m (k %.3f, "
          "delta %.1f deg) | strongest %.2f m (k %.3f) | run centre %.2f m (k %.3f)\n",
          beam_deg, incidences_deg[i], limit_m, edge_m, edge_m / kAxisRange_m, edge_delta_deg,
          strongest_m, strongest_m / kAxisRange_m, centre_m, centre_m / kAxisRange_m);
      // The leading edge: at normal incidence the wall itself; beyond it, shorter with every step
      // of incidence and with every wider beam, and no farther than the -3 dB first return (the
      // threshold sits below the -3 dB level of these echoes).
      if (i == 0) {
        EXPECT_NEAR(edge_m, kAxisRange_m, bin_m) << beam_deg;
      } else {
        EXPECT_LT(edge_m, last_edge_m) << beam_deg << " deg, psi " << incidences_deg[i];
        EXPECT_LT(edge_m, previous_edge_m[i]) << beam_deg << " deg, psi " << incidences_deg[i];
      }
      EXPECT_LE(edge_m, limit_m + bin_m) << beam_deg << " deg, psi " << incidences_deg[i];
      last_edge_m = edge_m;
      previous_edge_m[i] = edge_m;
      // The strongest bin and a run's centre lie beyond the axis at every incidence: the pulse
      // and the receiver put the peak after the leading edge, and an oblique footprint's echo
      // spreads farther out than in.
      EXPECT_GT(strongest_m, kAxisRange_m + bin_m) << beam_deg << " deg, psi " << incidences_deg[i];
      EXPECT_GT(centre_m, strongest_m) << beam_deg << " deg, psi " << incidences_deg[i];
    }
  }
}

}  // namespace
}  // namespace msislab::sim
