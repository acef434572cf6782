#include "sim/sonar_physics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "geometry/angles.hpp"
#include "sim/random.hpp"

namespace msislab::sim {

double range_scale(const SonarConfig& sonar) {
  return sonar.water_sound_speed_mps ? sonar.sound_speed_mps / *sonar.water_sound_speed_mps : 1.0;
}

double max_physical_range_m(const SonarConfig& sonar) {
  return sonar.bins * sonar.bin_m / range_scale(sonar);
}

namespace {
/// sinc(x)^4 = 1/2 at x = this: where the two-way sinc^2 x sinc^2 pattern is down 3 dB.
constexpr double kSincHalfPower = 1.0019063576966067;
}  // namespace

double two_way_loss(double range_m, double absorption_db_per_m) {
  return std::exp(-two_way_absorption_per_m(absorption_db_per_m) * range_m) /
         two_way_spreading(range_m);
}

double two_way_absorption_per_m(double absorption_db_per_m) {
  return 0.2 * std::log(10.0) * absorption_db_per_m;
}

double two_way_spreading(double range_m) {
  const double r = std::max(range_m, 1.0);
  return r * r * r * r;
}

// Lambert's n = 2 and n = 1 without pow.
double backscatter_per_area(double strength, double cos_incidence, float exponent) {
  if (exponent == 2.0f) return strength * cos_incidence * cos_incidence;
  if (exponent == 1.0f) return strength * cos_incidence;
  return strength * std::pow(cos_incidence, static_cast<double>(exponent));
}

double pattern_1d(double angle_rad, double width_rad, BeamPattern shape) {
  const double u = 2.0 * angle_rad / width_rad;
  if (shape == BeamPattern::kGaussian) return std::exp(-0.5 * kLn2 * u * u);
  const double x = kSincHalfPower * u;
  if (std::abs(x) < 1e-6) return 1.0;
  const double sinc = std::sin(x) / x;
  return sinc * sinc;
}

double one_way_pattern(double azimuth_rad, double elevation_rad, const SonarConfig& sonar) {
  return pattern_1d(azimuth_rad, sonar.horizontal_beamwidth_deg * kDegToRad, sonar.beam_pattern) *
         pattern_1d(elevation_rad, sonar.vertical_beamwidth_deg * kDegToRad, sonar.beam_pattern);
}

std::vector<double> pulse_kernel(const SonarConfig& sonar) {
  const double pulse_m = sonar.sound_speed_mps * sonar.pulse_length_us * 1e-6 / 2.0;
  const double tail_m = sonar.sound_speed_mps * sonar.receiver_time_constant_us * 1e-6 / 2.0;
  if (pulse_m <= 0.0 && tail_m <= 0.0) return {1.0};
  constexpr int kSubsteps = 20;  // samples per bin
  const double dx_m = sonar.bin_m / kSubsteps;
  const int pulse_n = std::max(1, static_cast<int>(std::lround(pulse_m / dx_m)));
  // The receiver's tail to 1e-4 of its start, then the pulse box run through it.
  const int tail_n = tail_m > 0.0 ? static_cast<int>(std::ceil(tail_m * std::log(1e4) / dx_m)) : 0;
  std::vector<double> fine(static_cast<std::size_t>(pulse_n + tail_n + 1), 0.0);
  for (int i = 0; i < pulse_n; ++i) {
    if (tail_n == 0) {
      fine[i] += 1.0;
      continue;
    }
    for (int k = 0; k <= tail_n; ++k) fine[i + k] += std::exp(-k * dx_m / tail_m);
  }
  std::vector<double> kernel;
  double total = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    const auto m = static_cast<std::size_t>((static_cast<double>(i) + 0.5) / kSubsteps);
    if (m >= kernel.size()) kernel.resize(m + 1, 0.0);
    kernel[m] += fine[i];
    total += fine[i];
  }
  for (double& k : kernel) k /= total;
  return kernel;
}

void spread_in_range(const std::vector<double>& kernel, std::vector<double>& power) {
  if (kernel.size() <= 1) return;
  std::vector<double> out(power.size(), 0.0);
  for (std::size_t j = 0; j < power.size(); ++j) {
    if (power[j] == 0.0) continue;
    const std::size_t end = std::min(power.size(), j + kernel.size());
    for (std::size_t k = j; k < end; ++k) out[k] += kernel[k - j] * power[j];
  }
  power.swap(out);
}

namespace {

/// The unit Gaussian at lattice corner (i, j, k): a hash of the corner through Box-Muller.
double corner_value(std::int64_t i, std::int64_t j, std::int64_t k) {
  std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull ^
                    static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full ^
                    static_cast<std::uint64_t>(k) * 0x165667B19E3779F9ull;
  const std::uint64_t a = splitmix64(h), b = splitmix64(a);
  const double u1 = (static_cast<double>(a >> 11) + 0.5) * 0x1.0p-53;
  const double u2 = unit_interval(b);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);  // Box-Muller
}

/// The corner values of the lattice cells recently used on this thread: neighbouring rays hit
/// neighbouring points, so most cells repeat, and eight hashes, logs, square roots and cosines
/// are saved each time (the values are the same).
class CellCache {
 public:
  const std::array<double, 8>& corners(std::int64_t i, std::int64_t j, std::int64_t k) {
    if (last_ != nullptr && last_->i == i && last_->j == j && last_->k == k) return last_->values;
    const std::uint64_t slot =
        (static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
         static_cast<std::uint64_t>(k) * 83492791u) &
        (kSlots - 1);
    Entry& e = entries_[slot];
    last_ = &e;
    if (!e.filled || e.i != i || e.j != j || e.k != k) {
      e.i = i;
      e.j = j;
      e.k = k;
      e.filled = true;
      for (int c = 0; c < 8; ++c) {
        e.values[static_cast<std::size_t>(c)] =
            corner_value(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
      }
    }
    return e.values;
  }

 private:
  static constexpr std::uint64_t kSlots = 256;
  struct Entry {
    std::int64_t i = 0, j = 0, k = 0;
    std::array<double, 8> values{};
    bool filled = false;
  };
  std::array<Entry, kSlots> entries_{};
  const Entry* last_ = nullptr;  ///< the cell of the last call
};

}  // namespace

double roughness_field(const Eigen::Vector3f& p_m, double length_m) {
  thread_local CellCache cells;
  const Eigen::Vector3d q = p_m.cast<double>() / length_m;
  const Eigen::Vector3d f = q.array().floor();
  const Eigen::Vector3d t = q - f;
  const std::array<double, 8>& v =
      cells.corners(static_cast<std::int64_t>(f.x()), static_cast<std::int64_t>(f.y()),
                    static_cast<std::int64_t>(f.z()));
  // Trilinear interpolation (corner c at offsets c & 1, c & 2, c & 4), and sum_c w_c^2, which
  // separates into a product over the axes of (1 - t)^2 + t^2.
  const auto lerp = [](double a, double b, double w) { return a + w * (b - a); };
  const double x00 = lerp(v[0], v[1], t.x()), x10 = lerp(v[2], v[3], t.x());
  const double x01 = lerp(v[4], v[5], t.x()), x11 = lerp(v[6], v[7], t.x());
  const double value = lerp(lerp(x00, x10, t.y()), lerp(x01, x11, t.y()), t.z());
  const auto squares = [](double w) { return (1.0 - w) * (1.0 - w) + w * w; };
  return value / std::sqrt(squares(t.x()) * squares(t.y()) * squares(t.z()));
}
}  // namespace msislab::sim
