#include "report/method_styles.hpp"

#include <algorithm>
#include <iterator>

namespace msislab::report {

namespace {

plot::SeriesStyle line_named(const std::string& name) {
  if (name == "dashed") return plot::SeriesStyle::kDashedLine;
  if (name == "dotted") return plot::SeriesStyle::kDottedLine;
  if (name == "points") return plot::SeriesStyle::kPoints;
  return plot::SeriesStyle::kLine;
}

}  // namespace

MethodStyles::MethodStyles()
    : styles_{
          {"robocentric", "Robocentric SLAM", 0x2ca02c, plot::SeriesStyle::kLine},
          // Dashed, so that where it coincides with the robocentric line (the same estimate,
          // docs/trajectory_slam.md) both show.
          {"worldcentric", "World-centric SLAM", 0x1f77b4, plot::SeriesStyle::kDashedLine},
          {"posegraph", "Pose graph (Ceres)", 0x9467bd, plot::SeriesStyle::kDottedLine},
          {"deadreckoning", "Dead reckoning", 0xd62728, plot::SeriesStyle::kLine},
          {"integration", "DVL integration", 0xff7f0e, plot::SeriesStyle::kLine},
      } {}

MethodStyles::MethodStyles(const settings::MethodsFile& file) : MethodStyles() {
  for (const settings::ExternalMethod& external : file.methods) {
    MethodStyle style{external.name, external.title,
                      external.colour ? *external.colour : name_colour(external.name),
                      line_named(external.line_style)};
    const auto it = std::find_if(styles_.begin(), styles_.end(),
                                 [&](const MethodStyle& s) { return s.name == external.name; });
    if (it == styles_.end()) {
      styles_.push_back(std::move(style));
    } else {
      *it = std::move(style);
    }
  }
}

const MethodStyle* MethodStyles::find(const std::string& name) const {
  const auto it = std::find_if(styles_.begin(), styles_.end(),
                               [&](const MethodStyle& s) { return s.name == name; });
  return it == styles_.end() ? nullptr : &*it;
}

std::string MethodStyles::title(const std::string& name) const {
  const MethodStyle* style = find(name);
  return style ? style->title : name;
}

std::uint32_t MethodStyles::colour(const std::string& name) const {
  const MethodStyle* style = find(name);
  return style ? style->colour : name_colour(name);
}

plot::SeriesStyle MethodStyles::line(const std::string& name) const {
  const MethodStyle* style = find(name);
  return style ? style->line : plot::SeriesStyle::kLine;
}

std::size_t MethodStyles::rank(const std::string& name) const {
  const MethodStyle* style = find(name);
  return style ? static_cast<std::size_t>(style - styles_.data()) : styles_.size();
}

std::uint32_t name_colour(const std::string& name) {
  static const std::uint32_t others[] = {0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22};
  std::size_t sum = 0;
  for (const char ch : name) sum += static_cast<unsigned char>(ch);
  return others[sum % std::size(others)];
}

}  // namespace msislab::report
