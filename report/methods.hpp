// The method registry: every estimator msislab can run, with what the commands need to know of it
// (its name on the command line, its title and colour in figures and tables, its kind and how to
// start it). `run`, `montecarlo`, `plot` and `report` all read it; adding a method is one entry.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "plot/chart.hpp"
#include "slam/scan_slam.hpp"
#include "slam/slam_config.hpp"

namespace msislab::report {

enum class MethodKind {
  kIntegration,     ///< DVL velocities integrated with the MRU heading, no filter
  kDeadReckoning,   ///< the DVL + MRU EKF; also places the scans by it when there is sonar data
  kTrajectorySlam,  ///< dead reckoning, then a SLAM back end over its scans (filter or graph)
};

struct MethodInfo {
  std::string name;   ///< on the command line and in result files
  std::string title;  ///< in figures and tables
  std::uint32_t colour = 0x000000;
  plot::SeriesStyle style = plot::SeriesStyle::kLine;  ///< where methods are compared
  MethodKind kind = MethodKind::kDeadReckoning;
  /// kTrajectorySlam: the back end, from the SLAM config and the start pose.
  std::function<std::unique_ptr<ScanSlam>(const SlamConfig&, const GaussianPose2&)> make_slam;
};

/// Every method, in the order tables list them (the paper's two filters, then the baselines).
const std::vector<MethodInfo>& methods();

/// The method of that name; nullptr when there is none.
const MethodInfo* find_method(const std::string& name);

/// The method of that name; InputError "OPTION 'm': not available in this build (available:
/// ...)" when there is none.
const MethodInfo& method_info(const std::string& name, const std::string& option = "--method");

/// The names, in registry order.
std::vector<std::string> method_names();

/// A method's title, or the name itself for a method this build does not know (an old result).
std::string method_title(const std::string& name);
/// A method's colour; an unknown one gets a fixed colour of its own from its name.
std::uint32_t method_colour(const std::string& name);
/// A method's line style where methods are compared; solid for an unknown one.
plot::SeriesStyle method_style(const std::string& name);
/// Where its row goes in a table: its registry index; unknown methods after all of them.
std::size_t method_rank(const std::string& name);

}  // namespace msislab::report
