// The sonar's physics as plain functions (docs/simulator.md): the transducer's beam pattern, the
// spread of an echo in range by the pulse and the receiver, and the roughness that varies a
// surface's backscatter along it. sim/msis builds the beams from them.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/scenario.hpp"

namespace msislab::sim {

/// The scale the sonar's ranges carry: a surface at range r is reported at r times this,
/// sound_speed_mps / water_sound_speed_mps (exactly 1 when the water's speed is not given).
double range_scale(const SonarConfig& sonar);
/// The farthest surface whose echo returns within the sonar's listening window, m:
/// bins x bin_m / range_scale.
double max_physical_range_m(const SonarConfig& sonar);

/// Two-way transmission loss, linear power ratio: spherical spreading 1/r^4 and absorption
/// 2 alpha r dB (Urick), exp(-two_way_absorption_per_m(alpha) r) / two_way_spreading(r). Falls
/// strictly with range. The receiver applies the same two factors.
double two_way_loss(double range_m, double absorption_db_per_m);
/// 10^(-2 alpha r / 10) = exp(-this x r): the absorption of both ways as a rate, 1/m.
double two_way_absorption_per_m(double absorption_db_per_m);
/// The spreading of both ways as the divisor r^4, r at least 1 m.
double two_way_spreading(double range_m);

/// strength x cos^n(incidence): a surface's backscatter per unit area (n = 2: Lambert).
double backscatter_per_area(double strength, double cos_incidence, float exponent);

/// One-way power pattern in one plane: 1 on the axis, 1/sqrt(2) (so -3 dB two-way) at
/// +-width/2. Gaussian exp(-ln2 u^2 / 2), or sinc^2(x) of a uniformly driven line aperture, with
/// u = 2a / width and x scaled so that sinc^4 = 1/2 at u = 1.
double pattern_1d(double angle_rad, double width_rad, BeamPattern shape);

/// The one-way power pattern of the head: the product of the two planes' patterns.
double one_way_pattern(double azimuth_rad, double elevation_rad, const SonarConfig& sonar);

/// The echo's range extent from the pulse and the receiver, as weights over bin offsets 0, 1, ...
/// (sum 1): a rectangular pulse of c tau / 2 in range convolved with the one-pole receiver's
/// exponential response exp(-2 x / (c tau_rx)), integrated over each bin; {1} when both are 0.
std::vector<double> pulse_kernel(const SonarConfig& sonar);

/// out[j] = sum_m kernel[m] power[j - m]: each bin's echo spread over the later bins.
void spread_in_range(const std::vector<double>& kernel, std::vector<double>& power);

/// A smooth, zero-mean Gaussian field of unit variance with correlation length `length_m`: value
/// noise (independent normal values at the corners of a cubic lattice, hashed from the corner's
/// indices), interpolated with the trilinear weights w_c and divided by sqrt(sum w_c^2), so its
/// variance is 1 at every point, on the lattice or between. No seed: it belongs to the surfaces,
/// the same in every ping and every run.
double roughness_field(const Eigen::Vector3f& p_m, double length_m);

}  // namespace msislab::sim
