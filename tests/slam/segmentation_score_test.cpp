// Segmentation scoring on hand-made beams whose hit, miss, wrong and false counts are known.
#include "slam/segmentation_score.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab {
namespace {

TEST(SegmentationScore, CountsHitsMissesWrongAndFalseDetections) {
  const std::vector<SegmentationTruth> truth = {
      {10.0, false},          // hit (one reading 0.2 m off) plus a false reading at 25 m
      {10.0, false},          // miss
      {10.0, true},           // wrong: 0.31 m off
      {20.0, true},           // hit exactly
      {std::nullopt, false},  // nothing on the axis: its reading is false
  };
  const std::vector<std::vector<double>> ranges_m = {{10.2, 25.0}, {}, {10.31}, {20.0}, {7.0}};
  const SegmentationScore s = score_segmentation(truth, ranges_m, 0.3);
  EXPECT_EQ(s.beams, 5u);
  EXPECT_EQ(s.beams_with_hit, 4u);
  EXPECT_EQ(s.beams_multipath, 2u);
  EXPECT_EQ(s.readings, 5u);
  EXPECT_DOUBLE_EQ(s.hit_fraction, 0.5);
  EXPECT_DOUBLE_EQ(s.miss_fraction, 0.25);
  EXPECT_DOUBLE_EQ(s.wrong_fraction, 0.25);
  EXPECT_DOUBLE_EQ(s.false_detection_fraction, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.hit_fraction_direct, 0.5);
  EXPECT_DOUBLE_EQ(s.hit_fraction_multipath, 0.5);
  EXPECT_NEAR(s.hit_range_rms_m, std::sqrt(0.2 * 0.2 / 2.0), 1e-12);
}

TEST(SegmentationScore, NearestReadingDecidesAndToleranceIsInclusive) {
  const std::vector<SegmentationTruth> truth = {{5.0, false}};
  const SegmentationScore s = score_segmentation(truth, {{4.0, 5.25, 6.0}}, 0.25);
  EXPECT_DOUBLE_EQ(s.hit_fraction, 1.0);
  EXPECT_DOUBLE_EQ(s.false_detection_fraction, 2.0 / 3.0);
  EXPECT_NEAR(s.hit_range_rms_m, 0.25, 1e-12);
}

TEST(SegmentationScore, EmptyDenominatorsAreNaN) {
  const std::vector<SegmentationTruth> truth = {{std::nullopt, false}};
  const SegmentationScore s = score_segmentation(truth, {{}}, 0.3);
  EXPECT_TRUE(std::isnan(s.hit_fraction));
  EXPECT_TRUE(std::isnan(s.hit_fraction_multipath));
  EXPECT_TRUE(std::isnan(s.false_detection_fraction));
  EXPECT_TRUE(std::isnan(s.hit_range_rms_m));
}

}  // namespace
}  // namespace msislab
