// One beam of the MSIS while it is rendered: the head at transmit and receive, the ping, each echo
// as it leaves a surface, and the echo profile gathered over the range bins. The tracer
// (sim/msis.cpp) makes the echoes, the receiver (sim/msis_receiver.hpp) lays them over the bins.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace msislab::sim {

/// Where the head is and where it points.
struct SonarHead {
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  double axis_azimuth_rad = 0.0;                    ///< world azimuth of the beam axis
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  ///< [cos, sin] of that azimuth
};

/// One beam's transmission: the head at transmit and at the latest possible receive time (the
/// echo from maximum range); receive poses in between are interpolated (tens of ms, a few cm).
struct Ping {
  double t_s = 0.0;
  double bearing_vehicle_rad = 0.0;
  SonarHead tx;
  SonarHead rx_last;
  double rx_window_s = 0.0;
};

/// One echo as it leaves a surface toward the receiver.
struct Echo {
  Eigen::Vector3f first_hit_m = Eigen::Vector3f::Zero();  ///< the route's first surface
  double path_m = 0.0;                                    ///< one-way length of the route
  double extent_m = 0.0;  ///< range extent of the footprint (0: a point)
  /// Transmit pattern x specular factors x backscatter x footprint area, times exp(log_gain):
  /// the log-normal roughness is kept as its exponent so that the receiver takes one exp.
  double power = 0.0;
  double log_gain = 0.0;
  bool multipath = false;  ///< came by a specular bounce
  std::uint32_t material_id = 0;
};

/// Received power over the range bins, direct and by specular routes.
struct EchoProfile {
  std::vector<double> direct;     ///< power per bin by direct backscatter
  std::vector<double> multipath;  ///< power per bin by a specular route
  /// Echoes spread over many bins add a constant power per bin to a run of bins: the change of
  /// that constant at each bin, summed into the profiles once all rays are in (O(1) per ray).
  std::vector<double> direct_steps;
  std::vector<double> multipath_steps;
  /// Every echo as laid over the bins, so the truth can name the surface that gave the most to
  /// any one bin.
  struct Contribution {
    long first = 0, last = 0;  ///< bins [first, last]
    double at_first = 0.0, at_last = 0.0, between = 0.0;
    std::uint32_t material_id = 0;
    Eigen::Vector3f first_hit_m = Eigen::Vector3f::Zero();  ///< the echo's first surface
    double at(long j) const {
      if (j == first) return at_first;
      if (j == last) return at_last;
      return j > first && j < last ? between : 0.0;
    }
  };
  std::vector<Contribution> contributions;

  /// Empties the profile for a beam of `bins` bins, keeping the memory.
  void reset(int bins) {
    const auto n = static_cast<std::size_t>(bins);
    direct.assign(n, 0.0);
    multipath.assign(n, 0.0);
    direct_steps.assign(n + 1, 0.0);
    multipath_steps.assign(n + 1, 0.0);
    contributions.clear();
  }

  /// Adds the spread echoes (the steps' running sums) into the profiles.
  void settle() {
    for (auto [steps, profile] :
         {std::pair{&direct_steps, &direct}, {&multipath_steps, &multipath}}) {
      double level = 0.0;
      for (std::size_t j = 0; j < profile->size(); ++j) {
        level += (*steps)[j];
        (*profile)[j] += level;
      }
    }
  }
};

}  // namespace msislab::sim
