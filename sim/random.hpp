// Every random number in the simulator comes from the scenario seed through these streams, so the
// same seed gives the same bytes whatever the thread count: each beam and each sensor gets its own
// generator, derived from (seed, stream, index) by splitmix64.
#pragma once

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

/// An independent generator for one (stream, index) of a seeded run.
inline std::mt19937_64 make_rng(std::uint64_t seed, RandomStream stream, std::uint64_t index) {
  const std::uint64_t key =
      splitmix64(splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(stream)) ^ index);
  std::seed_seq seq{static_cast<std::uint32_t>(key), static_cast<std::uint32_t>(key >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace msislab::sim
