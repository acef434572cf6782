#include "slam/segmentation_score.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace msislab {
namespace {

double fraction(std::size_t part, std::size_t whole) {
  if (whole == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(part) / static_cast<double>(whole);
}

// Running counts before they become fractions.
struct Tally {
  std::size_t hits = 0;
  std::size_t misses = 0;
  std::size_t wrong = 0;
  std::size_t false_readings = 0;
  std::size_t hits_direct = 0;
  std::size_t hits_multipath = 0;
  double squared_error_m2 = 0.0;
};

// The reading nearest the first hit, as a signed error (m).
double nearest_error_m(const std::vector<double>& ranges_m, double first_hit_m) {
  double best_m = std::numeric_limits<double>::infinity();
  for (const double r : ranges_m) {
    if (std::abs(r - first_hit_m) < std::abs(best_m)) best_m = r - first_hit_m;
  }
  return best_m;
}

void tally_beam(const SegmentationTruth& truth, const std::vector<double>& ranges_m,
                double tolerance_m, Tally& tally) {
  if (!truth.first_hit_range_m) {
    tally.false_readings += ranges_m.size();
    return;
  }
  const double first_hit_m = *truth.first_hit_range_m;
  for (const double r : ranges_m) {
    if (std::abs(r - first_hit_m) > tolerance_m) ++tally.false_readings;
  }
  if (ranges_m.empty()) {
    ++tally.misses;
    return;
  }
  const double error_m = nearest_error_m(ranges_m, first_hit_m);
  if (std::abs(error_m) > tolerance_m) {
    ++tally.wrong;
    return;
  }
  ++tally.hits;
  ++(truth.strongest_multipath ? tally.hits_multipath : tally.hits_direct);
  tally.squared_error_m2 += error_m * error_m;
}

}  // namespace

SegmentationScore score_segmentation(const std::vector<SegmentationTruth>& truth,
                                     const std::vector<std::vector<double>>& ranges_m,
                                     double tolerance_m) {
  assert(truth.size() == ranges_m.size());
  SegmentationScore score;
  Tally tally;
  score.beams = truth.size();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    score.readings += ranges_m[i].size();
    if (truth[i].first_hit_range_m) {
      ++score.beams_with_hit;
      if (truth[i].strongest_multipath) ++score.beams_multipath;
    }
    tally_beam(truth[i], ranges_m[i], tolerance_m, tally);
  }
  score.hit_fraction = fraction(tally.hits, score.beams_with_hit);
  score.miss_fraction = fraction(tally.misses, score.beams_with_hit);
  score.wrong_fraction = fraction(tally.wrong, score.beams_with_hit);
  score.false_detection_fraction = fraction(tally.false_readings, score.readings);
  score.hit_fraction_direct =
      fraction(tally.hits_direct, score.beams_with_hit - score.beams_multipath);
  score.hit_fraction_multipath = fraction(tally.hits_multipath, score.beams_multipath);
  score.hit_range_rms_m = tally.hits == 0
                              ? std::numeric_limits<double>::quiet_NaN()
                              : std::sqrt(tally.squared_error_m2 / static_cast<double>(tally.hits));
  return score;
}

}  // namespace msislab
