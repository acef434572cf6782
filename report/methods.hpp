// The method registry: every estimator msislab can run, with what the commands need to know of it
// (its name on the command line, its title and colour in figures and tables, its kind and how to
// start it). `run`, `montecarlo`, `plot` and `report` all read it; adding a method is one entry.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "io/methods_file.hpp"
#include "plot/chart.hpp"
#include "slam/scan_slam.hpp"
#include "slam/slam_config.hpp"

namespace msislab::report {

enum class MethodKind {
  kIntegration,     ///< DVL velocities integrated with the MRU heading, no filter
  kDeadReckoning,   ///< the DVL + MRU EKF; also places the scans by it when there is sonar data
  kTrajectorySlam,  ///< dead reckoning, then a SLAM back end over its scans (filter or graph)
  kExternal,        ///< a program of the user's, declared in a methods file (docs/formats.md)
};

struct MethodInfo {
  std::string name;   ///< on the command line and in result files
  std::string title;  ///< in figures and tables
  std::uint32_t colour = 0x000000;
  plot::SeriesStyle style = plot::SeriesStyle::kLine;  ///< where methods are compared
  MethodKind kind = MethodKind::kDeadReckoning;
  /// kTrajectorySlam: the back end, from the SLAM config and the start pose.
  std::function<std::unique_ptr<ScanSlam>(const SlamConfig&, const GaussianPose2&)> make_slam;
  /// kExternal: the command that runs it and its limits.
  std::optional<io::ExternalMethod> external;
};

/// Every method, in the order tables list them (the paper's two filters, then the baselines, then
/// the external methods registered).
const std::vector<MethodInfo>& methods();

/// The built-in methods' names (what a methods file may not declare).
std::vector<std::string> builtin_method_names();

/// Adds the methods of a methods file (read by io::read_methods_file with builtin_method_names())
/// after the built-in ones; one registered before under the same name is replaced. Call before
/// any MethodInfo reference is held: the registry may move.
void register_external_methods(const io::MethodsFile& file);

/// Reads the methods file at `path` and registers its methods; nothing for an empty path.
/// Throws io::InputError.
void load_methods_file(const std::string& path);

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
/// The fixed colour an unknown method gets from its name.
std::uint32_t name_colour(const std::string& name);
/// A method's line style where methods are compared; solid for an unknown one.
plot::SeriesStyle method_style(const std::string& name);
/// Where its row goes in a table: its registry index; unknown methods after all of them.
std::size_t method_rank(const std::string& name);

}  // namespace msislab::report
