// The MSIS model: losses fall with range, the beam schedule, a wall at a known range, motion
// inside a ping and inside a revolution, a surface-bounce ghost, and determinism.
#include "sim/msis.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "sim/random.hpp"

namespace msislab::sim {
namespace {

/// A wall x = wall_x_m (y in +-200 m, z from -50 to +1), facing -x, and nothing else.
TriangleMesh wall_mesh(float wall_x_m) {
  TriangleMesh mesh;
  mesh.vertices_m = {
      {wall_x_m, -200, -50}, {wall_x_m, 200, -50}, {wall_x_m, 200, 1}, {wall_x_m, -200, 1}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  mesh.material_ids = {0, 0};
  mesh.materials = {Material{"wall", 0.6f, 0.3f}};
  mesh.group_names = {"wall"};
  return mesh;
}

/// A vehicle at the origin pointing along +x, moving at speed_mps, for 30 s.
VehicleTrajectory straight(double speed_mps, double t0_s = 0.0) {
  std::vector<VehicleState> samples;
  for (int k = 0; k <= 3000; ++k) {
    const double t = t0_s + 0.01 * k;
    samples.push_back({t, Pose2(speed_mps * (t - t0_s), 0.0, 0.0), speed_mps, 0.0, 0.0});
  }
  return VehicleTrajectory(samples);
}

/// Sonar with its head at the vehicle origin and transducer angle 0 looking forward.
SonarConfig forward_sonar() {
  SonarConfig sonar;
  sonar.mount.x_m = 0.0;
  sonar.mount.bearing_offset_rad = 0.0;
  sonar.mount.bearing_sign = 1.0;
  sonar.speckle = false;
  sonar.noise_level_db = -200.0;
  sonar.roughness_db = 0.0;  // the geometry tests want an even wall; roughness has its own test
  return sonar;
}

std::size_t peak_bin(const std::vector<std::uint8_t>& intensity) {
  return static_cast<std::size_t>(std::max_element(intensity.begin(), intensity.end()) -
                                  intensity.begin());
}

TEST(Msis, LossFallsStrictlyWithRangeAndAbsorption) {
  for (double r = 1.0; r < 100.0; r += 0.5) {
    EXPECT_GT(two_way_loss(r, 0.0354), two_way_loss(r + 0.5, 0.0354)) << "r = " << r;
    EXPECT_GT(two_way_loss(r, 0.0), two_way_loss(r, 0.1)) << "r = " << r;
  }
  // 40 log r + 2 alpha r: at 10 m with alpha 0.05 dB/m, 40 + 1 dB.
  EXPECT_NEAR(10.0 * std::log10(two_way_loss(10.0, 0.05)), -41.0, 1e-9);
}

TEST(Msis, TwoHundredBeamsPerRevolutionWithTheAngleSteppingDown) {
  SonarConfig sonar;
  const auto slots = beam_schedule(sonar, 100.0, 100.0 + 10 * sonar.revolution_s - 1e-6);
  ASSERT_EQ(slots.size(), 2000u);
  const double step_rad = 2.0 * M_PI / 200.0;
  for (std::size_t k = 1; k < slots.size(); ++k) {
    EXPECT_NEAR(slots[k].t_s - slots[k - 1].t_s, 13.8 / 200.0, 1e-9);
    const double d =
        normalize_angle(slots[k].transducer_angle_rad - slots[k - 1].transducer_angle_rad);
    EXPECT_NEAR(d, -step_rad, 1e-9);
  }
  EXPECT_NEAR(slots[200].t_s - slots[0].t_s, 13.8, 1e-9);
}

TEST(Msis, WallAtAKnownRangeGivesItsEcho) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  SonarConfig sonar = forward_sonar();
  sonar.vertical_beamwidth_deg = 10.0;  // keep the bottom-free scene's surface out of the beam
  const MsisModel model(scene, sonar, 10.0);
  Rng rng(1);
  const RenderedBeam beam = model.render({0, 0.0, 0.0}, straight(0.0), rng);
  ASSERT_TRUE(beam.truth.first_hit_range_m);
  EXPECT_NEAR(*beam.truth.first_hit_range_m, 20.0, 1e-4);
  ASSERT_TRUE(beam.truth.strongest_range_m);
  EXPECT_NEAR(*beam.truth.strongest_range_m, 20.0, 0.11);
  EXPECT_FALSE(beam.truth.strongest_is_multipath);
  EXPECT_EQ(beam.truth.strongest_surface, "wall");
  const std::size_t peak = peak_bin(beam.intensity);
  EXPECT_NEAR(static_cast<double>(peak + 1) * sonar.bin_m, 20.0, 0.11);
  EXPECT_GT(beam.intensity[peak], 100);
  // Looking away from the wall: no hit, no echo above the (silent) background.
  const RenderedBeam away = model.render({1, 0.0, M_PI}, straight(0.0), rng);
  EXPECT_FALSE(away.truth.first_hit_range_m);
  EXPECT_EQ(*std::max_element(away.intensity.begin(), away.intensity.end()), 0);
}

TEST(Msis, EchoWeakensWithRange) {
  SonarConfig sonar = forward_sonar();
  sonar.vertical_beamwidth_deg = 10.0;
  // No gain or TVG and a display spanning -100..0 dB: the bare loss shows without clipping.
  sonar.tvg_db_per_decade = 0.0;
  sonar.gain_db = 0.0;
  sonar.display_min_db = -100.0;
  sonar.display_max_db = 0.0;
  std::vector<int> peaks;
  for (const float wall_x : {5.0f, 10.0f, 20.0f, 40.0f}) {
    const Scene scene(wall_mesh(wall_x), Material{"surface", 0.001f, 0.9f});
    const MsisModel model(scene, sonar, 10.0);
    Rng rng(1);
    const RenderedBeam beam = model.render({0, 0.0, 0.0}, straight(0.0), rng);
    peaks.push_back(beam.intensity[peak_bin(beam.intensity)]);
  }
  EXPECT_GT(peaks.back(), 0);
  for (std::size_t i = 1; i < peaks.size(); ++i) EXPECT_LT(peaks[i], peaks[i - 1]);
}

// The head moves toward the wall while the sound travels: received range = (d_tx + d_rx) / 2 with
// d_rx = d - v (2 d / c), so the echo shows at d (1 - v / c). 75 m/s makes the shift 1 m at 20 m.
TEST(Msis, MotionInsideAPingShortensTheRange) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  SonarConfig sonar = forward_sonar();
  sonar.vertical_beamwidth_deg = 10.0;
  sonar.horizontal_beamwidth_deg = 0.5;
  const MsisModel model(scene, sonar, 10.0);
  Rng rng(1);
  const double v = 75.0;
  const RenderedBeam beam = model.render({0, 0.0, 0.0}, straight(v), rng);
  EXPECT_NEAR(*beam.truth.first_hit_range_m, 20.0, 1e-4);  // truth: distance at transmit
  EXPECT_NEAR(*beam.truth.strongest_range_m, 20.0 * (1.0 - v / sonar.sound_speed_mps), 0.11);
}

TEST(Msis, EachBeamOfARevolutionHasItsOwnPose) {
  const Scene scene(wall_mesh(30.0f), Material{"surface", 0.001f, 0.9f});
  const SonarConfig sonar = forward_sonar();
  const MsisModel model(scene, sonar, 1.5);
  const VehicleTrajectory truth = straight(0.5);
  const auto slots = beam_schedule(sonar, 0.0, 13.8 - 1e-6);
  ASSERT_EQ(slots.size(), 200u);
  for (const BeamSlot& slot : {slots[0], slots[100], slots[199]}) {
    Rng rng(1);
    const RenderedBeam beam = model.render(slot, truth, rng);
    EXPECT_NEAR(beam.truth.vehicle.x(), 0.5 * slot.t_s, 1e-9);
  }
}

// Tilted up under a flat surface: every ray meets the surface first, bounces down onto the wall,
// and the wall's echo returns by the same route: a multipath echo at the one-way route length.
TEST(Msis, SurfaceBounceMakesAFlaggedGhost) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.0f, 0.9f});
  SonarConfig sonar = forward_sonar();
  sonar.tilt_deg = -20.0;  // 20 deg up
  sonar.vertical_beamwidth_deg = 6.0;
  const double depth_m = 2.0;
  const MsisModel model(scene, sonar, depth_m);
  Rng rng(1);
  const RenderedBeam beam = model.render({0, 0.0, 0.0}, straight(0.0), rng);
  ASSERT_TRUE(beam.truth.strongest_range_m);
  EXPECT_TRUE(beam.truth.strongest_is_multipath);
  EXPECT_EQ(beam.truth.strongest_surface, "wall");  // seen by way of the surface mirror
  // Up to the surface and down to the wall along the mirror image: 20 m / cos(20 deg).
  EXPECT_NEAR(*beam.truth.strongest_range_m, 20.0 / std::cos(20.0 * M_PI / 180.0), 0.3);
  SonarConfig no_bounce = sonar;
  no_bounce.multipath_bounces = 0;
  const MsisModel direct_only(scene, no_bounce, depth_m);
  const RenderedBeam quiet = direct_only.render({0, 0.0, 0.0}, straight(0.0), rng);
  EXPECT_EQ(*std::max_element(quiet.intensity.begin(), quiet.intensity.end()), 0);
}

TEST(Msis, SameStreamSameBeamDifferentStreamDifferentSpeckle) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  const SonarConfig sonar;  // speckle and noise on
  const MsisModel model(scene, sonar, 1.5);
  Rng a = make_rng(42, RandomStream::kSonarBeam, 7);
  Rng b = make_rng(42, RandomStream::kSonarBeam, 7);
  Rng c = make_rng(43, RandomStream::kSonarBeam, 7);
  const BeamSlot slot{7, 0.5, 0.3};
  const auto beam_a = model.render(slot, straight(0.2), a).intensity;
  EXPECT_EQ(beam_a, model.render(slot, straight(0.2), b).intensity);
  EXPECT_NE(beam_a, model.render(slot, straight(0.2), c).intensity);
}

}  // namespace
}  // namespace msislab::sim
