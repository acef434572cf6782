// MsisModel's working state while it renders one beam: the head at transmit and receive, the
// ping, and the echoes gathered over the range bins. Shared by sim/msis.cpp, which traces the
// rays, and sim/msis_receiver.cpp, which receives their echoes; not part of the interface.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/msis.hpp"

namespace msislab::sim {

struct MsisModel::Head {
  Eigen::Vector3f position_m;
  double axis_azimuth_rad = 0.0;                    ///< world azimuth of the beam axis
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  ///< [cos, sin] of that azimuth
};

/// One beam's transmission: the head at transmit and at the latest possible receive time (the
/// echo from maximum range); receive poses in between are interpolated (tens of ms, a few cm).
struct MsisModel::Ping {
  double t_s = 0.0;
  double bearing_vehicle_rad = 0.0;
  Head tx;
  Head rx_last;
  double rx_window_s = 0.0;
};

struct MsisModel::Echoes {
  explicit Echoes(int bins)
      : direct(bins, 0.0),
        multipath(bins, 0.0),
        direct_steps(bins + 1, 0.0),
        multipath_steps(bins + 1, 0.0) {}
  std::vector<double> direct;     ///< power per bin by direct backscatter
  std::vector<double> multipath;  ///< power per bin by a specular route
  /// Echoes spread over many bins add a constant power per bin to a run of bins: the change of
  /// that constant at each bin, summed into the profiles once all rays are in (O(1) per ray).
  std::vector<double> direct_steps;
  std::vector<double> multipath_steps;
  /// Every ray's echo as laid over the bins, so the truth can name the surface that gave the
  /// most to any one bin.
  struct Contribution {
    long first = 0, last = 0;  ///< bins [first, last]
    double at_first = 0.0, at_last = 0.0, between = 0.0;
    std::uint32_t material_id = 0;
    double at(long j) const {
      if (j == first) return at_first;
      if (j == last) return at_last;
      return j > first && j < last ? between : 0.0;
    }
  };
  std::vector<Contribution> contributions;

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
