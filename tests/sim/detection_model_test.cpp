// The St. Pere detector on synthetic profiles with known answers: MATLAB's movmean (its documented
// examples, odd and even windows), the smoothing widening a box echo by half a window each side and
// keeping it centred, the range ramp over the kept bins cutting a flat profile where ramp +
// threshold reaches it, the strict threshold, the near bins dropped before the smoothing, and the
// window shrinking at both ends of the kept bins. Every answer is exact.
#include "sim/detection_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace msislab::sim {
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

TEST(DetectionModel, MovingMeanIsMatlabsMovmean) {
  // MATLAB's documentation examples: movmean(A, 3) and movmean(A, 4) of the same vector. An even
  // window reaches w/2 back and w/2 - 1 ahead; both shrink at the ends.
  const std::vector<double> a = {4, 8, 6, -1, -2, -3, -1, 3, 4, 5};
  const std::vector<double> three = {6, 6,  4.3333333333333333, 1, -2, -2, -0.3333333333333333, 2,
                                     4, 4.5};
  const std::vector<double> four = {6, 6, 4.25, 2.75, 0, -1.75, -0.75, 0.75, 2.75, 4.0};
  const std::vector<double> m3 = moving_mean(a, 3), m4 = moving_mean(a, 4);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(m3[i], three[i], 1e-12) << i;
    EXPECT_NEAR(m4[i], four[i], 1e-12) << i;
  }
  EXPECT_EQ(moving_mean(a, 1), a);
  EXPECT_TRUE(moving_mean({}, 5).empty());
}

TEST(DetectionModel, AnIsolatedEchoStaysCentredUnderAnyWindow) {
  // A 3-bin echo centred on bin 200, far from the ends: the detected run is centred on it within
  // one bin (an even window, one bin off centre by construction, shifts it by half a bin).
  Profile p(kBins, 0);
  for (int j = 199; j <= 201; ++j) p[j] = 255;
  for (const int w : {1, 4, 5, 9, 11}) {
    DetectionModelConfig config;
    config.smoothing_bins = w;
    const std::vector<int> run = detect_bins(p, kBin_m, config);
    ASSERT_FALSE(run.empty()) << w;
    EXPECT_EQ(static_cast<std::size_t>(run.back() - run.front() + 1), run.size()) << w;
    EXPECT_LE(std::abs(0.5 * (run.front() + run.back()) - 200.0), 1.0) << w;
  }
}

TEST(DetectionModel, RangeRampEndsAFlatProfile) {
  // The ramp runs over the kept bins 9..499 (linspace(0, 30, 491)):
  // 60 - 30 (j - 9) / 490 > 45  <=>  j - 9 < 245  <=>  j <= 253; bins under 1 m (j < 9) dropped.
  const Profile p(kBins, 60);
  EXPECT_EQ(detect_bins(p, kBin_m, {}), range_of_bins(9, 253));
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

TEST(DetectionModel, DroppedNearBinsNeverEnterAMean) {
  // Bins under 1 m at full intensity: the real detector drops them before smoothing, so the
  // first kept bin (j = 9) sees only its own zeros and the two after it.
  Profile p(kBins, 0);
  for (int j = 0; j < 9; ++j) p[j] = 255;
  EXPECT_TRUE(detect_bins(p, kBin_m, {}).empty());
  // At the start of the kept bins the window shrinks too: at j = 9, 10, 11 it holds 3, 4 and 5
  // kept bins with the one strong bin, means 85, 63.75 and 51 (> 45 + ramp); at j = 12 none.
  p[9] = 255;
  EXPECT_EQ(detect_bins(p, kBin_m, {}), (std::vector<int>{9, 10, 11}));
}

TEST(DetectionModel, WindowShrinksAtTheEnds) {
  // A lone strong last bin: the window there holds the last 3 bins only, mean 255 / 3 = 85,
  // minus the full ramp 30 = 55 > 45; one bin earlier 4 bins, 63.75 - 29.94 = 33.8 < 45.
  Profile p(kBins, 0);
  p[kBins - 1] = 255;
  EXPECT_EQ(detect_bins(p, kBin_m, {}), std::vector<int>{kBins - 1});
}

TEST(DetectionModel, EmptyAndShortProfiles) {
  EXPECT_TRUE(detect_bins({}, kBin_m, {}).empty());
  DetectionModelConfig near;
  near.min_range_m = 0.0;
  // One kept bin: MATLAB's linspace(0, 30, 1) is 30, so 200 - 30 > 45.
  EXPECT_EQ(detect_bins(Profile{200}, kBin_m, near), std::vector<int>{0});
  EXPECT_TRUE(detect_bins(Profile{70}, kBin_m, near).empty());
  EXPECT_TRUE(detect_bins(Profile(5, 255), kBin_m, {}).empty());  // nothing beyond 1 m
}

/// A revolution of `beams` identical rows: the kept bins (491, from 1.0 m) of a profile with an
/// E-bin box echo of 200 starting at bin 200.
std::vector<std::vector<double>> box_revolution(int echo_bins, int beams = 200) {
  Profile p(kBins, 0);
  for (int j = 200; j < 200 + echo_bins; ++j) p[j] = 200;
  return std::vector<std::vector<double>>(static_cast<std::size_t>(beams),
                                          kept_bins(p, kBin_m, 1.0));
}

TEST(DetectionModel, MatlabsDefaultWindowIsAboutTheEchosWidth) {
  // smoothdata's rule (0.44294 x 2N / (rho - 1) for the -3 dB point where three quarters of the
  // energy lie below): a box echo of E bins gives a window of about E.
  ASSERT_EQ(box_revolution(8).front().size(), 491u);
  EXPECT_EQ(matlab_default_window(box_revolution(4)), 4);
  EXPECT_EQ(matlab_default_window(box_revolution(8)), 8);
  EXPECT_EQ(matlab_default_window(box_revolution(12)), 12);
  EXPECT_EQ(matlab_default_window(box_revolution(20)), 19);
  EXPECT_EQ(matlab_default_window(box_revolution(40)), 37);
}

TEST(DetectionModel, ConstantBeamsCountAsNoEnergyInTheDefaultWindow) {
  // A constant beam's normalised spectrum is 0/0, which MATLAB's cumsum(..., 'omitnan') counts as
  // zeros: with a quarter of the beams constant the average never exceeds 0.75 (window 1), with
  // a fifth it reaches 0.75 later (a wider band: a narrower window).
  std::vector<std::vector<double>> rows = box_revolution(8, 3);
  rows.push_back(std::vector<double>(491, 0.0));
  EXPECT_EQ(matlab_default_window(rows), 1);
  rows = box_revolution(8, 4);
  rows.push_back(std::vector<double>(491, 7.0));
  EXPECT_EQ(matlab_default_window(rows), 3);
  EXPECT_EQ(matlab_default_window({}), 1);
}

}  // namespace
}  // namespace msislab::sim
