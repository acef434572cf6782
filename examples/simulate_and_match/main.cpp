// Simulates two revolutions of a mechanically scanned imaging sonar in a basin with a channel,
// from two poses 1.5 m and 8 degrees apart, turns each beam's nearest return into a scan point
// and matches the second scan against the first with spIC: what a user's own code on msislab's
// libraries looks like. Prints the match against the true relative pose; exits 1 when the match
// is not valid or misses the truth by 0.3 m or 1 degree or more.
#include <cmath>
#include <cstdio>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "sim/msis.hpp"
#include "sim/random.hpp"
#include "sim/scene.hpp"
#include "sim/scene_builder.hpp"
#include "slam/beam_segmentation.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_matching.hpp"

namespace {

using namespace msislab;

/// The vehicle held at one pose for a revolution.
sim::VehicleTrajectory hold(const Pose2& pose_world, double t0_s, double duration_s) {
  return sim::VehicleTrajectory(
      {{t0_s, pose_world, 0.0, 0.0, 0.0}, {t0_s + duration_s, pose_world, 0.0, 0.0, 0.0}});
}

/// One revolution seen from `pose_world`: each beam's nearest return as a point in the
/// vehicle frame, with a reading covariance of a bin along the beam and the beamwidth across it.
std::vector<ScanPoint> revolution(const sim::MsisModel& sonar_model, const sim::SonarConfig& sonar,
                                  const Pose2& pose_world, std::uint64_t seed) {
  const sim::VehicleTrajectory still = hold(pose_world, 0.0, sonar.revolution_s);
  std::vector<ScanPoint> points;
  for (const sim::BeamSlot& slot : sim::beam_schedule(sonar, 0.0, sonar.revolution_s - 1e-6)) {
    sim::Rng rng(seed + slot.index);
    const sim::RenderedBeam beam = sonar_model.render(slot, still, rng);
    // The pipeline's segmentation of a raw profile: the nearest run above the threshold.
    const std::vector<double> ranges_m =
        segment_profile(beam.intensity, sonar.bin_m, SegmentationConfig{});
    if (ranges_m.empty()) continue;
    const double range_m = ranges_m.front();
    const double bearing_rad = beam.truth.bearing_vehicle_rad;
    const Eigen::Vector2d along(std::cos(bearing_rad), std::sin(bearing_rad));
    const Eigen::Vector2d across(-along.y(), along.x());
    const double across_m = range_m * sonar.horizontal_beamwidth_deg * M_PI / 180.0 / 2.0;
    ScanPoint point;
    point.p_m = Eigen::Vector2d(sonar.mount.x_m, 0.0) + range_m * along;
    point.p_vehicle_m = point.p_m;
    point.cov = sonar.bin_m * sonar.bin_m * along * along.transpose() +
                across_m * across_m * across * across.transpose();
    point.cov_reading = point.cov;
    point.t_s = slot.t_s;
    points.push_back(point);
  }
  return points;
}

}  // namespace

int main() {
  // The scene: a 60 m square basin with a 16 m wide channel leaving its east side, 8 m deep with
  // a mud bottom (shallower, the beam's lower edge finds the bottom a few metres out and every
  // beam's nearest return is the same ring around the vehicle, which no match can use).
  sim::MeshBuilder builder;
  const std::uint32_t walls = builder.group("walls", 0.6f, 0.3f);
  const std::uint32_t bottom = builder.group("bottom", 0.01f, 0.1f);
  sim::BasinProfile profile;
  profile.z_bottom_m = -8.0;
  sim::add_basin(builder, sim::channel_basin_outline(sim::ChannelBasin{}), profile, walls, bottom);
  const sim::Scene scene(builder.mesh(), sim::Material{"surface", 0.0f, 0.9f});

  sim::SonarConfig sonar;  // the St. Pere head's defaults: 200 steps, 500 bins of 0.1 m
  const sim::MsisModel sonar_model(scene, sonar, 1.0);
  const Pose2 first_world(-8.0, -5.0, 0.3);
  const Pose2 second_world = first_world.compose(Pose2(1.5, 0.2, 8.0 * M_PI / 180.0));
  const std::vector<ScanPoint> reference = revolution(sonar_model, sonar, first_world, 1);
  const std::vector<ScanPoint> current = revolution(sonar_model, sonar, second_world, 2);

  // The guess: the truth off by 0.3 m and 2 degrees, with the uncertainty dead reckoning would
  // give over a revolution.
  const Pose2 truth = first_world.between(second_world);
  GaussianPose2 guess;
  guess.mean = truth.compose(Pose2(0.3, -0.2, 2.0 * M_PI / 180.0));
  guess.cov = Eigen::Vector3d(0.5 * 0.5, 0.5 * 0.5, std::pow(4.0 * M_PI / 180.0, 2)).asDiagonal();
  const ScanMatchResult match = match_scans(reference, current, guess, ScanMatchConfig{});

  std::printf("scan points: %zu and %zu\n", reference.size(), current.size());
  std::printf("truth:  x %.3f m, y %.3f m, yaw %.2f deg\n", truth.x(), truth.y(),
              truth.yaw() * 180.0 / M_PI);
  std::printf("spIC:   x %.3f m, y %.3f m, yaw %.2f deg (%s, %d pairs)\n", match.estimate.mean.x(),
              match.estimate.mean.y(), match.estimate.mean.yaw() * 180.0 / M_PI,
              match.valid ? "valid" : "not valid", match.inliers);
  if (!match.valid) return 1;
  const Eigen::Vector3d error = pose_difference(match.estimate.mean, truth);
  const double nees = error.dot(match.estimate.cov.ldlt().solve(error));
  std::printf("error:  %.3f m, %.2f deg; NEES %.2f against spIC's covariance\n",
              error.head<2>().norm(), error.z() * 180.0 / M_PI, nees);
  return error.head<2>().norm() < 0.3 && std::abs(error.z()) < M_PI / 180.0 ? 0 : 1;
}
