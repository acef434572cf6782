// Synthetic scans for the spIC and match-validation tests: a harbour-like corner, and points with
// isotropic Gaussian noise whose covariance is all their own reading noise.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "slam/scan_builder.hpp"
#include "tests/draws.hpp"

namespace msislab::testing_scans {

/// A harbour-like corner: three walls sampled every 0.5 m, in the reference frame.
inline std::vector<Eigen::Vector2d> corner_walls() {
  std::vector<Eigen::Vector2d> points;
  for (double s = -10.0; s <= 15.0; s += 0.5) points.emplace_back(s, 12.0);          // north wall
  for (double s = -8.0; s <= 12.0; s += 0.5) points.emplace_back(15.0, s);           // east wall
  for (double s = 0.0; s <= 6.0; s += 0.5) points.emplace_back(-4.0 + s, -8.0 + s);  // a mole
  return points;
}

/// The points, each moved by N(0, sigma^2 I), with that covariance.
inline std::vector<ScanPoint> noisy(const std::vector<Eigen::Vector2d>& points, double sigma_m,
                                    std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma_m);
  std::vector<ScanPoint> out;
  for (const auto& p : points) {
    ScanPoint sp;
    sp.p_m = p + draws_last_first<2>([&] { return n(rng); });
    sp.cov = sigma_m * sigma_m * Eigen::Matrix2d::Identity();
    sp.cov_reading = sp.cov;  // all of it is the point's own noise
    out.push_back(sp);
  }
  return out;
}

}  // namespace msislab::testing_scans
