// Beam segmentation on synthetic profiles with known answers: each method on single and double
// echoes, a multipath ghost behind a wall, noise, saturation, the minimum range and a lone spike;
// the detections path; method names. Ranges are compared to 1e-9 m (bin centres are exact).
#include "slam/beam_segmentation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace msislab {
namespace {

constexpr double kBin_m = 0.1;
constexpr double kTol_m = 1e-9;
constexpr std::size_t kBins = 500;

using Profile = std::vector<std::uint8_t>;

// Bin j lies at (j + 1) x 0.1 m.
std::size_t bin_at(double range_m) { return static_cast<std::size_t>(range_m / kBin_m + 0.5) - 1; }

// A low noise floor (below any threshold used here) with echoes added by the tests.
Profile floor_profile() {
  Profile p(kBins);
  for (std::size_t j = 0; j < kBins; ++j) p[j] = static_cast<std::uint8_t>(10 + (j * 7) % 20);
  return p;
}

// A three-bin echo whose peak is at peak_range_m: shoulders at 60% of the peak.
void add_echo(Profile& p, double peak_range_m, std::uint8_t peak) {
  const std::size_t j = bin_at(peak_range_m);
  const auto shoulder = static_cast<std::uint8_t>(peak * 6 / 10);
  p[j - 1] = std::max(p[j - 1], shoulder);
  p[j] = peak;
  p[j + 1] = std::max(p[j + 1], shoulder);
}

SegmentationConfig config_for(SegmentationMethod method) {
  SegmentationConfig config;
  config.method = method;
  config.threshold = 80.0;
  config.min_range_m = 1.0;
  config.max_ranges_per_beam = 1;
  config.min_run_bins = 1;
  config.smoothing_bins = 3;
  return config;
}

const std::vector<SegmentationMethod> kMethods = {SegmentationMethod::kMaxIntensity,
                                                  SegmentationMethod::kThresholdGroups,
                                                  SegmentationMethod::kSmoothedFirst};

std::vector<double> segment(const Profile& p, SegmentationMethod method) {
  return segment_profile(p, kBin_m, config_for(method));
}

TEST(BeamSegmentation, SingleEchoIsFoundByEveryMethod) {
  Profile p = floor_profile();
  add_echo(p, 12.3, 200);
  for (const SegmentationMethod method : kMethods) {
    const std::vector<double> ranges_m = segment(p, method);
    ASSERT_EQ(ranges_m.size(), 1u) << to_string(method);
    EXPECT_NEAR(ranges_m[0], 12.3, kTol_m) << to_string(method);
  }
}

TEST(BeamSegmentation, TwoEchoesGiveTheNearestGroupsInOrder) {
  Profile p = floor_profile();
  add_echo(p, 8.0, 150);
  add_echo(p, 20.0, 250);  // stronger and farther
  SegmentationConfig config = config_for(SegmentationMethod::kThresholdGroups);
  const std::vector<double> one_m = segment_profile(p, kBin_m, config);
  ASSERT_EQ(one_m.size(), 1u);
  EXPECT_NEAR(one_m[0], 8.0, kTol_m);
  config.max_ranges_per_beam = 2;
  const std::vector<double> two_m = segment_profile(p, kBin_m, config);
  ASSERT_EQ(two_m.size(), 2u);
  EXPECT_NEAR(two_m[0], 8.0, kTol_m);
  EXPECT_NEAR(two_m[1], 20.0, kTol_m);
  // The strongest bin wins for kMaxIntensity, the first run for kSmoothedFirst.
  EXPECT_NEAR(segment(p, SegmentationMethod::kMaxIntensity).at(0), 20.0, kTol_m);
  EXPECT_NEAR(segment(p, SegmentationMethod::kSmoothedFirst).at(0), 8.0, kTol_m);
}

TEST(BeamSegmentation, FirstReturnMethodsTakeTheWallBeforeAStrongerGhost) {
  Profile p = floor_profile();
  add_echo(p, 6.0, 140);   // the wall
  add_echo(p, 11.5, 230);  // its multipath ghost, stronger after TVG
  EXPECT_NEAR(segment(p, SegmentationMethod::kThresholdGroups).at(0), 6.0, kTol_m);
  EXPECT_NEAR(segment(p, SegmentationMethod::kSmoothedFirst).at(0), 6.0, kTol_m);
  EXPECT_NEAR(segment(p, SegmentationMethod::kMaxIntensity).at(0), 11.5, kTol_m);
}

TEST(BeamSegmentation, NoiseBelowTheThresholdGivesNoRange) {
  const Profile p = floor_profile();
  for (const SegmentationMethod method : kMethods) {
    EXPECT_TRUE(segment(p, method).empty()) << to_string(method);
  }
}

TEST(BeamSegmentation, SaturatedRunGivesOneRangeInsideIt) {
  Profile p = floor_profile();
  const std::size_t begin = bin_at(15.0);
  const std::size_t end = bin_at(15.8) + 1;  // 255 over 15.0 .. 15.8 m
  for (std::size_t j = begin; j < end; ++j) p[j] = 255;
  EXPECT_NEAR(segment(p, SegmentationMethod::kMaxIntensity).at(0), 15.0, kTol_m);
  SegmentationConfig config = config_for(SegmentationMethod::kThresholdGroups);
  config.max_ranges_per_beam = 3;
  for (const SegmentationMethod method :
       {SegmentationMethod::kThresholdGroups, SegmentationMethod::kSmoothedFirst}) {
    config.method = method;
    const std::vector<double> ranges_m = segment_profile(p, kBin_m, config);
    ASSERT_EQ(ranges_m.size(), 1u) << to_string(method);
    EXPECT_GE(ranges_m[0], 15.0 - kTol_m) << to_string(method);
    EXPECT_LE(ranges_m[0], 15.8 + kTol_m) << to_string(method);
  }
}

TEST(BeamSegmentation, EchoCloserThanTheMinimumRangeIsIgnored) {
  Profile p = floor_profile();
  add_echo(p, 0.6, 255);  // ring-down or the vehicle itself
  add_echo(p, 9.0, 120);
  for (const SegmentationMethod method : kMethods) {
    const std::vector<double> ranges_m = segment(p, method);
    ASSERT_EQ(ranges_m.size(), 1u) << to_string(method);
    EXPECT_NEAR(ranges_m[0], 9.0, kTol_m) << to_string(method);
  }
}

TEST(BeamSegmentation, BinExactlyAtTheMinimumRangeIsKept) {
  Profile p = floor_profile();
  p[bin_at(1.0)] = 200;  // range 1.0 m, the minimum
  EXPECT_NEAR(segment(p, SegmentationMethod::kThresholdGroups).at(0), 1.0, kTol_m);
  p[bin_at(1.0)] = 10;
  p[bin_at(0.9)] = 200;  // one bin closer
  EXPECT_TRUE(segment(p, SegmentationMethod::kThresholdGroups).empty());
}

TEST(BeamSegmentation, SmoothingSuppressesASingleBinSpike) {
  Profile p = floor_profile();
  p[bin_at(4.0)] = 150;  // speckle spike: one bin, mean over 3 bins about 65 < 80
  add_echo(p, 18.0, 220);
  EXPECT_NEAR(segment(p, SegmentationMethod::kThresholdGroups).at(0), 4.0, kTol_m);
  EXPECT_NEAR(segment(p, SegmentationMethod::kSmoothedFirst).at(0), 18.0, kTol_m);
}

TEST(BeamSegmentation, MinRunBinsDropsShortRuns) {
  Profile p = floor_profile();
  p[bin_at(4.0)] = 150;
  add_echo(p, 18.0, 220);
  SegmentationConfig config = config_for(SegmentationMethod::kThresholdGroups);
  config.min_run_bins = 2;
  EXPECT_NEAR(segment_profile(p, kBin_m, config).at(0), 18.0, kTol_m);
}

TEST(BeamSegmentation, DetectionsFormRunsAcrossOneBinGaps) {
  SegmentationConfig config = config_for(SegmentationMethod::kThresholdGroups);
  config.max_ranges_per_beam = 3;
  // 0.5 m is under the minimum range; 3.0-3.4 m has one missing bin (3.2); 5.0 m is two missing
  // bins after 4.7 m, so a new return; unsorted input.
  const std::vector<double> detected_m = {0.5, 3.1, 3.0, 3.3, 3.4, 4.7, 5.0, 5.1, 9.0};
  const std::vector<double> ranges_m = segment_detections(detected_m, kBin_m, config);
  ASSERT_EQ(ranges_m.size(), 3u);
  EXPECT_NEAR(ranges_m[0], 3.2, 1e-12);
  EXPECT_NEAR(ranges_m[1], 4.7, 1e-12);
  EXPECT_NEAR(ranges_m[2], 5.05, 1e-12);
  config.max_ranges_per_beam = 1;
  EXPECT_EQ(segment_detections(detected_m, kBin_m, config).size(), 1u);
  EXPECT_TRUE(segment_detections({0.2, 0.9}, kBin_m, config).empty());
  EXPECT_TRUE(segment_detections({}, kBin_m, config).empty());
}

TEST(BeamSegmentation, MethodNamesRoundTrip) {
  for (const SegmentationMethod method : kMethods) {
    SegmentationMethod parsed = method == SegmentationMethod::kMaxIntensity
                                    ? SegmentationMethod::kSmoothedFirst
                                    : SegmentationMethod::kMaxIntensity;
    ASSERT_TRUE(parse_segmentation_method(to_string(method), parsed)) << to_string(method);
    EXPECT_EQ(parsed, method);
  }
  SegmentationMethod untouched = SegmentationMethod::kSmoothedFirst;
  EXPECT_FALSE(parse_segmentation_method("threshold", untouched));
  EXPECT_FALSE(parse_segmentation_method("", untouched));
  EXPECT_EQ(untouched, SegmentationMethod::kSmoothedFirst);
}

}  // namespace
}  // namespace msislab
