#include "app/method_catalogue.hpp"

#include <algorithm>

#include "io/input_error.hpp"
#include "slam/scan_slam_pipeline.hpp"

namespace msislab::app {

namespace {

Method slam_method(const std::string& name, ScanSlamBackend backend) {
  return {name, MethodKind::kTrajectorySlam,
          [backend](const SlamConfig& config, const GaussianPose2& start) {
            return make_scan_slam(backend, config, start);
          },
          std::nullopt};
}

}  // namespace

MethodCatalogue::MethodCatalogue()
    : methods_{
          slam_method("robocentric", ScanSlamBackend::kRobocentric),
          slam_method("worldcentric", ScanSlamBackend::kWorldcentric),
          // The modern baseline: the same front end on a Ceres pose graph. Its trajectory.tum
          // is the online estimate, trajectory_smoothed.tum the smoothed one.
          slam_method("posegraph", ScanSlamBackend::kPoseGraph),
          {"deadreckoning", MethodKind::kDeadReckoning, {}, std::nullopt},
          {"integration", MethodKind::kIntegration, {}, std::nullopt},
      } {}

MethodCatalogue MethodCatalogue::with_methods_file(const std::string& path) {
  MethodCatalogue catalogue;
  if (path.empty()) return catalogue;
  // read_methods_file refuses a built-in name and a name declared twice.
  catalogue.file_ = settings::read_methods_file(path, builtin_names());
  for (const settings::ExternalMethod& external : catalogue.file_.methods) {
    catalogue.methods_.push_back({external.name, MethodKind::kExternal, {}, external});
  }
  return catalogue;
}

std::vector<std::string> MethodCatalogue::builtin_names() { return MethodCatalogue().names(); }

std::vector<std::string> MethodCatalogue::names() const {
  std::vector<std::string> names;
  for (const Method& m : methods_) names.push_back(m.name);
  return names;
}

const Method* MethodCatalogue::find(const std::string& name) const {
  const auto it = std::find_if(methods_.begin(), methods_.end(),
                               [&](const Method& m) { return m.name == name; });
  return it == methods_.end() ? nullptr : &*it;
}

const Method& MethodCatalogue::at(const std::string& name, const std::string& option) const {
  if (const Method* method = find(name)) return *method;
  std::string list;
  for (const std::string& m : names()) list += (list.empty() ? "" : ", ") + m;
  throw io::InputError(option + " '" + name + "': not available in this build (available: " + list +
                       ")");
}

}  // namespace msislab::app
