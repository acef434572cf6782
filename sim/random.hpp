// Every random number in the simulator comes from the scenario seed through these streams, so the
// same seed gives the same bytes whatever the thread count: each beam and each sensor gets its own
// generator, derived from (seed, stream, index) by splitmix64.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace msislab::sim {

enum class RandomStream : std::uint64_t { kSonarBeam = 1, kDvl = 2, kMru = 3, kGps = 4 };

/// splitmix64 finaliser: a well-mixed 64-bit value from any 64-bit input.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// A double uniform in [0, 1) from the top 53 bits of a 64-bit random word.
inline double unit_interval(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// xoshiro256** (Blackman and Vigna): a small, fast generator with a 2^256 period whose state is
/// seeded by splitmix64, so a generator per beam costs four multiplications to create. Meets the
/// UniformRandomBitGenerator requirements, so the <random> distributions take it.
class Xoshiro256 {
 public:
  using result_type = std::uint64_t;
  explicit Xoshiro256(std::uint64_t seed) {
    for (std::uint64_t& word : state_) word = seed = splitmix64(seed);
  }
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }
  result_type operator()() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

using Rng = Xoshiro256;

/// Unit-mean exponential variates from a table of 4096 quantiles (the midpoints of equal
/// probability cells): one generator call and one lookup instead of a logarithm. The largest
/// value is -ln(1/8192) = 9.0, so the tail beyond it (probability 1.2e-4) folds into the last cell.
class ExponentialTable {
 public:
  ExponentialTable() {
    for (std::size_t i = 0; i < kSize; ++i) {
      table_[i] = -std::log(1.0 - (static_cast<double>(i) + 0.5) / kSize);
    }
  }
  double operator()(Rng& rng) const { return table_[rng() >> (64 - kBits)]; }
  /// The largest value drawn, -ln(1 / 8192).
  static double max() { return std::log(2.0 * kSize); }

 private:
  static constexpr int kBits = 12;
  static constexpr std::size_t kSize = std::size_t{1} << kBits;
  double table_[kSize];
};

/// An independent generator for one (stream, index) of a seeded run.
inline Rng make_rng(std::uint64_t seed, RandomStream stream, std::uint64_t index) {
  return Rng(splitmix64(splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(stream)) ^ index));
}

/// Two draws as a vector, the y coordinate drawn before x: the order in which g++ evaluates the
/// arguments of Eigen::Vector2d(draw(), draw()), which C++ leaves unspecified (clang goes left to
/// right). Written out so that a dataset does not depend on the compiler that built msislab, and
/// is the one g++ builds have always made.
template <class Draw>
Eigen::Vector2d draw_y_then_x(Draw&& draw) {
  const double y = draw();
  const double x = draw();
  return {x, y};
}

}  // namespace msislab::sim
