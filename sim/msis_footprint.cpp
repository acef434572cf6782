// The surface patch a ray of the MSIS stands for (docs/simulator.md): its area and its extent in
// range on the surface it hits, and the roughness that varies the surface's backscatter along it.
#include <algorithm>
#include <cmath>

#include "sim/msis.hpp"
#include "sim/sonar_physics.hpp"

namespace msislab::sim {

namespace {
/// At grazing incidence a footprint's area and extent grow without bound as 1 / cos; the beam
/// bounds them in fact, so cos(incidence) is taken as at least this.
constexpr double kMinFootprintCos = 0.02;
}  // namespace

double MsisModel::footprint_extent(double path_m, const Eigen::Vector3f& direction,
                                   const Eigen::Vector3f& cell_azimuth,
                                   const Eigen::Vector3f& cell_elevation,
                                   const Eigen::Vector3f& normal) const {
  if (!sonar_.footprint) return 0.0;
  // A surface at distance t along d, normal n: t(d) = const / (d . n), so a change dd of the
  // direction moves the hit by dt = -t (dd . n) / (d . n). Over the cell's two edges the ranges
  // cover two boxes; their sum has the variance of a box of width sqrt(w_a^2 + w_e^2).
  constexpr double kMaxExtent_m = 10.0;
  const double cos_incidence =
      std::max(std::abs(static_cast<double>(direction.dot(normal))), kMinFootprintCos);
  const double w_azimuth = path_m * std::abs(cell_azimuth.dot(normal)) / cos_incidence;
  const double w_elevation = path_m * std::abs(cell_elevation.dot(normal)) / cos_incidence;
  // Both widths are bounded (path <= the sonar's range, cos >= kMinFootprintCos): no overflow.
  return std::min(std::sqrt(w_azimuth * w_azimuth + w_elevation * w_elevation), kMaxExtent_m);
}

double MsisModel::footprint_area(double path_m, double cell_sr, double cos_incidence) const {
  if (!sonar_.footprint) return 1.0;
  return path_m * path_m * cell_sr / std::max(cos_incidence, kMinFootprintCos);
}

double MsisModel::roughness_log_gain(const Eigen::Vector3f& point_m) const {
  if (sonar_.roughness_db <= 0.0) return 0.0;
  // Log-normal with mean 1: 10^(sigma_dB g / 10) / E[.], g the unit field.
  const double sigma_ln = sonar_.roughness_db * std::log(10.0) / 10.0;
  return sigma_ln * roughness_field(point_m, sonar_.roughness_length_m) - 0.5 * sigma_ln * sigma_ln;
}

}  // namespace msislab::sim
