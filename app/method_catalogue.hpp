// The methods a command can run, as a value: the built-in ones (the paper's two filters, the pose
// graph over the same front end, dead reckoning, velocity integration) and the programs of a
// methods file (docs/formats.md). `run`, `montecarlo` and `sweep` make one from `--methods-file`
// and pass it to what runs a method. How figures show them is report/'s (report/method_styles.hpp,
// made from methods_file()): running a method knows nothing of presentation.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "settings/methods_file.hpp"
#include "slam/scan_slam.hpp"
#include "slam/slam_config.hpp"

namespace msislab::app {

enum class MethodKind {
  kIntegration,     ///< DVL velocities integrated with the MRU heading, no filter
  kDeadReckoning,   ///< the DVL + MRU EKF; also places the scans by it when there is sonar data
  kTrajectorySlam,  ///< dead reckoning, then a SLAM back end over its scans (filter or graph)
  kExternal,        ///< a program of the user's, declared in a methods file
};

struct Method {
  std::string name;  ///< on the command line and in result files
  MethodKind kind = MethodKind::kDeadReckoning;
  /// kTrajectorySlam: the back end, from the SLAM config and the start pose.
  std::function<std::unique_ptr<ScanSlam>(const SlamConfig&, const GaussianPose2&)> make_slam;
  /// kExternal: the command that runs it and its limits.
  std::optional<settings::ExternalMethod> external;
};

class MethodCatalogue {
 public:
  /// The built-in methods.
  MethodCatalogue();
  /// The built-in methods, then those of the methods file at `path` (none for an empty path).
  /// Throws io::InputError for a file read_methods_file refuses.
  static MethodCatalogue with_methods_file(const std::string& path);
  /// The built-in methods' names (what a methods file may not declare).
  static std::vector<std::string> builtin_names();

  /// In the order tables list them.
  const std::vector<Method>& methods() const { return methods_; }
  std::vector<std::string> names() const;
  /// The method of that name; nullptr when there is none.
  const Method* find(const std::string& name) const;
  /// The method of that name; InputError "OPTION 'm': not available in this build (available:
  /// ...)" when there is none.
  const Method& at(const std::string& name, const std::string& option = "--method") const;
  /// The methods file the external methods came from (no methods without one).
  const settings::MethodsFile& methods_file() const { return file_; }

 private:
  std::vector<Method> methods_;
  settings::MethodsFile file_;
};

}  // namespace msislab::app
