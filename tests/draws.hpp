// Random vectors for the tests, drawn in a fixed order. C++ leaves the order in which a
// constructor's arguments are evaluated unspecified: g++ evaluates Eigen::Vector2d(n(rng), n(rng))
// right to left, clang left to right, so the same seed gave the two compilers different draws
// (and the statistical tests different, equally valid, samples). These draw the last coordinate
// first, as g++ did, so every test keeps the samples its bounds were checked on whichever
// compiler builds it (the sanitizer suite builds with clang).
#pragma once

#include <Eigen/Core>

namespace msislab {

/// N draws, the last coordinate first.
template <int N, class Draw>
Eigen::Matrix<double, N, 1> draws_last_first(Draw&& draw) {
  Eigen::Matrix<double, N, 1> v;
  for (int i = N; i-- > 0;) v(i) = draw();
  return v;
}

}  // namespace msislab
