// The St. Pere detector on synthetic profiles with known answers: the smoothing widens a box echo
// by half a window each side, the range ramp cuts a flat profile where ramp + threshold reaches
// it, the threshold is strict, the minimum range drops near bins, and the window shrinks at the
// profile's ends. Every answer is exact (integers).
#include "sim/detection_model.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

namespace msislab {
namespace {

constexpr double kBin_m = 0.1;
constexpr int kBins = 500;

using Profile = std::vector<std::uint8_t>;

std::vector<int> range_of_bins(int first, int last) {
  std::vector<int> bins(static_cast<std::size_t>(last - first + 1));
  std::iota(bins.begin(), bins.end(), first);
  return bins;
}

TEST(DetectionModel, BoxEchoWidensByHalfTheWindowEachSide) {
  Profile p(kBins, 0);
  for (int j = 100; j < 110; ++j) p[j] = 200;
  // 5-bin mean: two box bins in the window give 80 (> 45 + ramp 6), one gives 40 (< 45).
  EXPECT_EQ(detect_bins(p, kBin_m, {}), range_of_bins(99, 110));
  DetectionModelConfig unsmoothed;
  unsmoothed.smoothing_bins = 1;
  EXPECT_EQ(detect_bins(p, kBin_m, unsmoothed), range_of_bins(100, 109));
}

TEST(DetectionModel, RangeRampEndsAFlatProfile) {
  // 60 - 30 j / 499 > 45  <=>  j < 249.5; bins under 1 m (j < 9) dropped.
  const Profile p(kBins, 60);
  EXPECT_EQ(detect_bins(p, kBin_m, {}), range_of_bins(9, 249));
}

TEST(DetectionModel, ThresholdIsStrict) {
  const Profile at(kBins, 45);
  DetectionModelConfig flat;
  flat.ramp_max = 0.0;
  EXPECT_TRUE(detect_bins(at, kBin_m, flat).empty());
  const Profile above(kBins, 46);
  EXPECT_EQ(detect_bins(above, kBin_m, flat).size(), static_cast<std::size_t>(kBins - 9));
}

TEST(DetectionModel, MinimumRangeDropsNearBins) {
  Profile p(kBins, 0);
  for (int j = 0; j < 30; ++j) p[j] = 255;
  DetectionModelConfig config;
  config.smoothing_bins = 1;
  config.min_range_m = 2.0;  // bin 19 is at exactly 2.0 m and stays
  EXPECT_EQ(detect_bins(p, kBin_m, config), range_of_bins(19, 29));
}

TEST(DetectionModel, WindowShrinksAtTheEnds) {
  // A lone strong last bin: the window there holds the last 3 bins only, mean 255 / 3 = 85,
  // minus the full ramp 30 = 55 > 45; one bin earlier 4 bins, 63.75 - 29.9 = 33.8 < 45.
  Profile p(kBins, 0);
  p[kBins - 1] = 255;
  EXPECT_EQ(detect_bins(p, kBin_m, {}), std::vector<int>{kBins - 1});
}

TEST(DetectionModel, EmptyAndShortProfiles) {
  EXPECT_TRUE(detect_bins({}, kBin_m, {}).empty());
  DetectionModelConfig near;
  near.min_range_m = 0.0;
  EXPECT_EQ(detect_bins(Profile{200}, kBin_m, near), std::vector<int>{0});
}

}  // namespace
}  // namespace msislab
