// The MSIS model: losses fall with range, the beam schedule, a wall at a known range, motion
// inside a ping and inside a revolution, a surface-bounce ghost, and determinism.
#include "sim/msis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/random.hpp"
#include "sim/sonar_physics.hpp"

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

/// No gain, TVG, pulse or receiver, the display spanning -100..0 dB (2.55 steps per dB): the
/// footprints' own echo shows without clipping.
SonarConfig bare_sonar() {
  SonarConfig sonar = forward_sonar();
  sonar.vertical_beamwidth_deg = 10.0;
  sonar.tvg_db_per_decade = 0.0;
  sonar.gain_db = 0.0;
  sonar.display_min_db = -100.0;
  sonar.display_max_db = 0.0;
  sonar.pulse_length_us = 0.0;
  sonar.receiver_time_constant_us = 0.0;
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

TEST(Msis, AReversedRotationStepsTheAngleUp) {
  SonarConfig sonar;
  sonar.rotation = SonarRotation::kIncreasing;
  const auto slots = beam_schedule(sonar, 0.0, 2 * sonar.revolution_s - 1e-6);
  ASSERT_EQ(slots.size(), 400u);
  const double step_rad = 2.0 * M_PI / 200.0;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    EXPECT_NEAR(slots[k].transducer_angle_rad, static_cast<double>(k % 200) * step_rad, 1e-12);
  }
}

TEST(Msis, APing360SectorScanSweepsBackAndForth) {
  // 400 steps a turn (one gradian), a 90 deg sector from 0 deg, turning up: 0, 0.9, ..., 90 deg,
  // then 89.1 down to 0.9, then 0 again: 200 beams a period, each end once.
  SonarConfig sonar;
  sonar.steps_per_revolution = 400;
  sonar.revolution_s = 400 * 0.02;
  sonar.rotation = SonarRotation::kIncreasing;
  sonar.sector = SonarSector{0, 100};
  const auto slots = beam_schedule(sonar, 0.0, 401 * 0.02 - 1e-9);
  ASSERT_EQ(slots.size(), 401u);
  const double step_deg = 0.9;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const std::size_t phase = k % 200;
    const double expected_deg = step_deg * static_cast<double>(phase <= 100 ? phase : 200 - phase);
    EXPECT_NEAR(slots[k].transducer_angle_rad * 180.0 / M_PI, expected_deg, 1e-9) << "beam " << k;
    EXPECT_NEAR(slots[k].t_s, 0.02 * static_cast<double>(k), 1e-9);
  }
  // Decreasing through 0: a sector from 10 deg down to 350 deg (20 deg across north).
  sonar.rotation = SonarRotation::kDecreasing;
  sonar.sector = SonarSector{11, 389};  // 9.9 deg and 350.1 deg
  const auto across = beam_schedule(sonar, 0.0, 50 * 0.02 - 1e-9);
  const std::vector<double> expected_deg = {9.9, 9.0, 8.1};
  for (std::size_t k = 0; k < expected_deg.size(); ++k) {
    EXPECT_NEAR(across[k].transducer_angle_rad * 180.0 / M_PI, expected_deg[k], 1e-9);
  }
  EXPECT_NEAR(across[22].transducer_angle_rad * 180.0 / M_PI, 350.1, 1e-9);  // the far end
  EXPECT_NEAR(across[23].transducer_angle_rad * 180.0 / M_PI, 351.0, 1e-9);  // and back
  EXPECT_NEAR(across[44].transducer_angle_rad * 180.0 / M_PI, 9.9, 1e-9);    // the first end
}

// A reading's source off the beam's axis (truth/beams.csv's strongest_bearing_offset_rad): a
// 1 m wide post 20 m ahead, 3 deg to the left of a 9 deg beam's axis, is the only surface; the
// strongest echo's source is on it, so its bearing offset lies within the post's +-1.43 deg of
// 3 deg, counter-clockwise positive. Not a statistic (no speckle, no roughness, no noise).
TEST(Msis, TheStrongestEchoKnowsHowFarOffTheAxisItsSourceLies) {
  for (const double side : {1.0, -1.0}) {
    const float y0 = static_cast<float>(side * 20.0 * std::tan(3.0 * M_PI / 180.0));
    TriangleMesh mesh;
    mesh.vertices_m = {
        {20, y0 - 0.5f, -50}, {20, y0 + 0.5f, -50}, {20, y0 + 0.5f, 1}, {20, y0 - 0.5f, 1}};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    mesh.material_ids = {0, 0};
    mesh.materials = {Material{"post", 0.6f, 0.0f}};
    mesh.group_names = {"post"};
    const Scene scene(mesh, Material{"surface", 0.001f, 0.9f});
    SonarConfig sonar = forward_sonar();
    sonar.vertical_beamwidth_deg = 10.0;
    sonar.horizontal_beamwidth_deg = 9.0;
    const MsisModel model(scene, sonar, 10.0);
    Rng rng(1);
    const RenderedBeam beam = model.render({0, 0.0, 0.0}, straight(0.0), rng);
    EXPECT_FALSE(beam.truth.first_hit_range_m);  // the axis misses the post
    ASSERT_TRUE(beam.truth.strongest_bearing_offset_rad);
    EXPECT_EQ(beam.truth.strongest_surface, "post");
    const double half_width_rad = std::atan(0.5 / 20.0);
    EXPECT_NEAR(*beam.truth.strongest_bearing_offset_rad, side * 3.0 * M_PI / 180.0,
                half_width_rad + 1e-3)
        << "side " << side;
  }
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
  // Not a statistic (speckle off, noise 200 dB down: the beam is the same on every stream,
  // Msis.WithoutSpeckleTheBeamIsTheSameOnEveryStream): 20.0 m; 0.11 m is a bin and its rounding.
  EXPECT_NEAR(*beam.truth.strongest_range_m, 20.0, 0.11);
  EXPECT_FALSE(beam.truth.strongest_is_multipath);
  EXPECT_EQ(beam.truth.strongest_surface, "wall");
  const std::size_t peak = peak_bin(beam.intensity);
  // The displayed peak comes after the pulse and the receiver: the pulse lasts c tau / 2 in range
  // (0.15 m), so the peak lies between the wall and the pulse's end (within a bin).
  const double peak_m = static_cast<double>(peak + 1) * sonar.bin_m;
  const double pulse_m = sonar.sound_speed_mps * sonar.pulse_length_us * 1e-6 / 2.0;
  EXPECT_GE(peak_m, 20.0 - 0.11);
  EXPECT_LE(peak_m, 20.0 + pulse_m + 0.11);
  EXPECT_GT(beam.intensity[peak], 100);  // not a statistic (no speckle): 160
  // Looking away from the wall: no hit, no echo above the (silent) background.
  const RenderedBeam away = model.render({1, 0.0, M_PI}, straight(0.0), rng);
  EXPECT_FALSE(away.truth.first_hit_range_m);
  EXPECT_EQ(*std::max_element(away.intensity.begin(), away.intensity.end()), 0);
}

TEST(Msis, EchoWeakensWithRange) {
  // No gain or TVG and a display spanning -100..0 dB: the bare loss shows without clipping.
  const SonarConfig sonar = bare_sonar();
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
  // Not a statistic (no speckle): 19.0 m; a bin and its rounding, where the motion moves it 1 m.
  EXPECT_NEAR(*beam.truth.strongest_range_m, 20.0 * (1.0 - v / sonar.sound_speed_mps), 0.11);
}

// A sonar that converts time to range with 1500 m/s in water where sound travels at 1440 m/s
// reports a wall at 20 m at 20 x 1500 / 1440 = 20.83 m: its ranges carry a scale of 1.042 (the
// range scale a SLAM back end can estimate, docs/trajectory_slam.md). The truth keeps the true
// distance; a wall beyond the shortened listening range (49.9 x 1440 / 1500 = 47.9 m) is unheard.
TEST(Msis, AWrongSoundSpeedScalesTheRanges) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  SonarConfig sonar = forward_sonar();
  sonar.vertical_beamwidth_deg = 10.0;
  sonar.horizontal_beamwidth_deg = 0.5;
  const double true_range_m = [&] {
    Rng rng(1);
    return *MsisModel(scene, sonar, 10.0)
                .render({0, 0.0, 0.0}, straight(0.0), rng)
                .truth.strongest_range_m;
  }();
  sonar.water_sound_speed_mps = 1440.0;
  EXPECT_NEAR(range_scale(sonar), 1500.0 / 1440.0, 1e-15);
  Rng rng(1);
  const RenderedBeam beam = MsisModel(scene, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
  EXPECT_NEAR(*beam.truth.first_hit_range_m, 20.0, 1e-4);
  // Not a statistic (no speckle): 20.9 against 20.83 m, a bin and its rounding.
  EXPECT_NEAR(*beam.truth.strongest_range_m, true_range_m * 1500.0 / 1440.0, 0.11);
  EXPECT_GT(*beam.truth.strongest_range_m, true_range_m + 0.7);

  const Scene far(wall_mesh(48.5f), Material{"surface", 0.001f, 0.9f});
  Rng far_rng(1);
  const RenderedBeam unheard =
      MsisModel(far, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), far_rng);
  EXPECT_EQ(*std::max_element(unheard.intensity.begin(), unheard.intensity.end()), 0);
  sonar.water_sound_speed_mps.reset();
  Rng near_rng(1);
  const RenderedBeam heard =
      MsisModel(far, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), near_rng);
  EXPECT_GT(*std::max_element(heard.intensity.begin(), heard.intensity.end()), 0);
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
  // Not a statistic (no speckle): 21.2 against 21.28 m; the direct wall at 20 m is 1.3 m away.
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

/// A wall through (range_m, 0) whose normal turns incidence_deg away from the beam axis (+x).
TriangleMesh turned_wall_mesh(float range_m, double incidence_deg) {
  const double phi = incidence_deg * M_PI / 180.0;
  const auto at = [&](double t, float z) {
    return Eigen::Vector3f(static_cast<float>(range_m - t * std::sin(phi)),
                           static_cast<float>(t * std::cos(phi)), z);
  };
  TriangleMesh mesh = wall_mesh(range_m);
  mesh.vertices_m = {at(-200, -50), at(200, -50), at(200, 1), at(-200, 1)};
  return mesh;
}

/// Bins within 10 dB (25.5 display steps) of the peak.
int bins_within_10_db(const std::vector<std::uint8_t>& intensity) {
  const int peak = intensity[peak_bin(intensity)];
  return static_cast<int>(std::count_if(intensity.begin(), intensity.end(),
                                        [&](std::uint8_t v) { return v + 25.5 >= peak; }));
}

// The tests here that bound a range or a level on one beam use sonars without speckle and with
// the noise 200 dB down: their beams do not depend on the random stream, so those bounds are the
// physics', not a sample's. Two streams, the same bytes and the same truth.
TEST(Msis, WithoutSpeckleTheBeamIsTheSameOnEveryStream) {
  const Scene scene(turned_wall_mesh(20.0f, 60.0), Material{"surface", 0.001f, 0.9f});
  for (const SonarConfig& sonar : {forward_sonar(), bare_sonar()}) {
    const MsisModel model(scene, sonar, 10.0);
    Rng a(1), b(2);
    const RenderedBeam one = model.render({0, 0.0, 0.0}, straight(0.0), a);
    const RenderedBeam other = model.render({0, 0.0, 0.0}, straight(0.0), b);
    EXPECT_EQ(one.intensity, other.intensity);
    EXPECT_EQ(one.truth.strongest_range_m, other.truth.strongest_range_m);
    EXPECT_GT(*std::max_element(one.intensity.begin(), one.intensity.end()), 0);
  }
}

// An oblique wall's echo covers the ranges its footprint spans: at 60 deg incidence and 20 m on
// the axis, the two-way pattern's -10 dB half width (1.5 deg x sqrt(10 / 3) = 2.74 deg) meets
// the wall from 10 / cos(57.26 deg) = 18.5 m to 10 / cos(62.74 deg) = 21.8 m, 33 bins; at normal
// incidence only the vertical lobe spreads it, 20 (1 / cos(9 deg) - 1) = 0.25 m.
TEST(Msis, ObliqueWallSmearsOverItsFootprint) {
  const SonarConfig sonar = bare_sonar();
  Rng rng(1);
  const Scene normal(turned_wall_mesh(20.0f, 0.0), Material{"surface", 0.001f, 0.9f});
  const RenderedBeam at_normal =
      MsisModel(normal, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
  EXPECT_LE(bins_within_10_db(at_normal.intensity), 4);  // not a statistic (no speckle): 3
  const Scene oblique(turned_wall_mesh(20.0f, 60.0), Material{"surface", 0.001f, 0.9f});
  const RenderedBeam at_60 =
      MsisModel(oblique, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
  EXPECT_NEAR(*at_60.truth.first_hit_range_m, 20.0, 1e-3);  // geometry, not a statistic
  const int extent = bins_within_10_db(at_60.intensity);
  std::printf("-10 dB extent: %d bins at normal incidence, %d at 60 deg\n",
              bins_within_10_db(at_normal.intensity), extent);
  // The far side loses to r^-2 and to its wider spread (dr/da grows as r tan(incidence)), about
  // 3 dB at the pattern's -10 dB edge, so the extent lies between the -3 dB pattern width (19.1
  // to 20.9 m, 18 bins) and the -10 dB one (33 bins). Measured: 32.
  // Not a statistic (no speckle): the -3 dB and -10 dB widths bound it.
  EXPECT_GE(extent, 15);
  EXPECT_LE(extent, 35);
  // With point echoes (no footprints) the 16 rays across the beam land in separate bins, and
  // few of them come within 10 dB of the strongest.
  SonarConfig points = sonar;
  points.footprint = false;
  const RenderedBeam point_echo =
      MsisModel(oblique, points, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
  EXPECT_LT(bins_within_10_db(point_echo.intensity), extent / 2);
}

// The material's incidence exponent n scales the echo of a wall met at incidence theta by
// cos^n(theta): at 60 deg, n = 0 returns 4x (6 dB, 15.3 display steps) what Lambert's n = 2 does,
// and at normal incidence the two agree.
TEST(Msis, IncidenceExponentSetsTheObliqueEcho) {
  const SonarConfig sonar = bare_sonar();
  Rng rng(1);
  const auto peak = [&](double incidence_deg, float exponent) {
    TriangleMesh mesh = turned_wall_mesh(20.0f, incidence_deg);
    mesh.materials[0].incidence_exponent = exponent;
    const Scene scene(mesh, Material{"surface", 0.001f, 0.9f});
    const RenderedBeam beam =
        MsisModel(scene, sonar, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
    return static_cast<double>(beam.intensity[peak_bin(beam.intensity)]);
  };
  // Each not a statistic (no speckle): 124 and 124, 15 and 8 display steps; the tolerances are
  // the display's rounding and the footprint's spread of incidences around 60 deg.
  EXPECT_NEAR(peak(0.0, 0.0f), peak(0.0, 2.0f), 1.0);
  EXPECT_NEAR(peak(60.0, 0.0f) - peak(60.0, 2.0f), 15.3, 2.0);
  EXPECT_NEAR(peak(60.0, 1.0f) - peak(60.0, 2.0f), 7.7, 2.0);  // not a statistic: 8
}

// With footprints the rays sample the beam's integral of b^2 over solid angle: four times the
// rays give the same echo level (within 0.5 dB, 1.3 display steps).
TEST(Msis, EchoLevelDoesNotDependOnTheRayCount) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  const SonarConfig sonar = bare_sonar();
  SonarConfig dense = sonar;
  dense.rays_horizontal *= 2;
  dense.rays_vertical *= 2;
  Rng rng(1);
  const auto level = [&](const SonarConfig& s) {
    const RenderedBeam beam = MsisModel(scene, s, 10.0).render({0, 0.0, 0.0}, straight(0.0), rng);
    return static_cast<int>(beam.intensity[peak_bin(beam.intensity)]);
  };
  EXPECT_NEAR(level(sonar), level(dense), 1.3);  // not a statistic (no speckle): 124 and 124
}

// Roughness belongs to the wall: the same patch gives the same echo in every ping, and along the
// wall the echo level varies by about roughness_db (less a little: each footprint averages a few
// metres of a field correlated over 10 m), smoothly.
TEST(Msis, RoughnessVariesTheWallAlongItsLengthAndNotFromPingToPing) {
  const Scene scene(wall_mesh(20.0f), Material{"surface", 0.001f, 0.9f});
  SonarConfig sonar = bare_sonar();
  sonar.roughness_db = 10.0;
  sonar.roughness_length_m = 10.0;
  const MsisModel model(scene, sonar, 10.0);
  std::vector<double> level_db;
  double step_change_db = 0.0;
  for (int k = 0; k < 400; ++k) {
    // The vehicle moves along the wall (y) at 1 m/s; the beam looks at the wall (+x).
    std::vector<VehicleState> samples;
    for (int i = 0; i <= 100; ++i) {
      samples.push_back({0.01 * i, Pose2(0.0, 0.5 * k, 0.0), 0.0, 0.0, 0.0});
    }
    const VehicleTrajectory at(samples);
    Rng a(1), b(2);
    const RenderedBeam beam = model.render({0, 0.0, 0.0}, at, a);
    EXPECT_EQ(beam.intensity, model.render({0, 0.0, 0.0}, at, b).intensity);
    level_db.push_back(beam.intensity[peak_bin(beam.intensity)] / 2.55);
    if (k > 0) step_change_db += std::abs(level_db[k] - level_db[k - 1]) / 399.0;
  }
  double mean = 0.0, var = 0.0;
  for (const double l : level_db) mean += l / static_cast<double>(level_db.size());
  for (const double l : level_db)
    var += (l - mean) * (l - mean) / static_cast<double>(level_db.size() - 1);
  std::printf("roughness 10 dB: echo level sd %.2f dB along 200 m, mean step over 0.5 m %.2f dB\n",
              std::sqrt(var), step_change_db);
  // Each not a statistic of the draws: the roughness field is a function of position (the same
  // on every stream, checked above), so these are one wall's numbers: 10.4 dB and 0.76 dB a step.
  EXPECT_GT(std::sqrt(var), 6.0);
  EXPECT_LT(std::sqrt(var), 12.0);
  EXPECT_LT(step_change_db, 2.0);  // not a statistic: 0.76
}

}  // namespace
}  // namespace msislab::sim
