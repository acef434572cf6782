#include "report/methods.hpp"

#include <algorithm>
#include <iterator>

#include "io/input_error.hpp"
#include "slam/scan_slam_pipeline.hpp"

namespace msislab::report {

namespace {

std::vector<MethodInfo> builtin_methods() {
  return {
      {"robocentric", "Robocentric SLAM", 0x2ca02c, plot::SeriesStyle::kLine,
       MethodKind::kTrajectorySlam,
       [](const SlamConfig& config, const GaussianPose2& start) {
         return make_scan_slam(ScanSlamBackend::kRobocentric, config, start);
       },
       std::nullopt},
      // Dashed, so that where it coincides with the robocentric line (the same estimate,
      // docs/trajectory_slam.md) both show.
      {"worldcentric", "World-centric SLAM", 0x1f77b4, plot::SeriesStyle::kDashedLine,
       MethodKind::kTrajectorySlam,
       [](const SlamConfig& config, const GaussianPose2& start) {
         return make_scan_slam(ScanSlamBackend::kWorldcentric, config, start);
       },
       std::nullopt},
      // The modern baseline: the same front end on a Ceres pose graph. Its
      // trajectory.tum is the online estimate, trajectory_smoothed.tum the smoothed one.
      {"posegraph", "Pose graph (Ceres)", 0x9467bd, plot::SeriesStyle::kDottedLine,
       MethodKind::kTrajectorySlam,
       [](const SlamConfig& config, const GaussianPose2& start) {
         return make_scan_slam(ScanSlamBackend::kPoseGraph, config, start);
       },
       std::nullopt},
      {"deadreckoning",
       "Dead reckoning",
       0xd62728,
       plot::SeriesStyle::kLine,
       MethodKind::kDeadReckoning,
       {},
       std::nullopt},
      {"integration",
       "DVL integration",
       0xff7f0e,
       plot::SeriesStyle::kLine,
       MethodKind::kIntegration,
       {},
       std::nullopt},
  };
}

std::vector<MethodInfo>& registry() {
  static std::vector<MethodInfo> all = builtin_methods();
  return all;
}

plot::SeriesStyle style_named(const std::string& name) {
  if (name == "dashed") return plot::SeriesStyle::kDashedLine;
  if (name == "dotted") return plot::SeriesStyle::kDottedLine;
  if (name == "points") return plot::SeriesStyle::kPoints;
  return plot::SeriesStyle::kLine;
}

}  // namespace

const std::vector<MethodInfo>& methods() { return registry(); }

std::vector<std::string> builtin_method_names() {
  std::vector<std::string> names;
  for (const MethodInfo& m : builtin_methods()) names.push_back(m.name);
  return names;
}

void register_external_methods(const io::MethodsFile& file) {
  std::vector<MethodInfo>& all = registry();
  for (const io::ExternalMethod& external : file.methods) {
    MethodInfo info;
    info.name = external.name;
    info.title = external.title;
    info.colour = external.colour ? *external.colour : name_colour(external.name);
    info.style = style_named(external.line_style);
    info.kind = MethodKind::kExternal;
    info.external = external;
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const MethodInfo& m) { return m.name == external.name; });
    if (it == all.end()) {
      all.push_back(std::move(info));
    } else if (it->kind == MethodKind::kExternal) {
      *it = std::move(info);
    } else {
      io::fail_file(file.path, "method '" + external.name + "' is a built-in method");
    }
  }
}

void load_methods_file(const std::string& path) {
  if (!path.empty()) register_external_methods(io::read_methods_file(path, builtin_method_names()));
}

const MethodInfo* find_method(const std::string& name) {
  const auto& all = methods();
  const auto it =
      std::find_if(all.begin(), all.end(), [&](const MethodInfo& m) { return m.name == name; });
  return it == all.end() ? nullptr : &*it;
}

const MethodInfo& method_info(const std::string& name, const std::string& option) {
  if (const MethodInfo* info = find_method(name)) return *info;
  std::string list;
  for (const std::string& m : method_names()) list += (list.empty() ? "" : ", ") + m;
  throw io::InputError(option + " '" + name + "': not available in this build (available: " + list +
                       ")");
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const MethodInfo& m : methods()) names.push_back(m.name);
  return names;
}

std::string method_title(const std::string& name) {
  const MethodInfo* info = find_method(name);
  return info ? info->title : name;
}

std::uint32_t method_colour(const std::string& name) {
  if (const MethodInfo* info = find_method(name)) return info->colour;
  return name_colour(name);
}

std::uint32_t name_colour(const std::string& name) {
  static const std::uint32_t others[] = {0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22};
  std::size_t sum = 0;
  for (const char ch : name) sum += static_cast<unsigned char>(ch);
  return others[sum % std::size(others)];
}

plot::SeriesStyle method_style(const std::string& name) {
  const MethodInfo* info = find_method(name);
  return info ? info->style : plot::SeriesStyle::kLine;
}

std::size_t method_rank(const std::string& name) {
  const MethodInfo* info = find_method(name);
  return info ? static_cast<std::size_t>(info - methods().data()) : methods().size();
}

}  // namespace msislab::report
