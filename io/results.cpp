#include "io/results.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"

namespace msislab::io {

std::string json_number(double value) {
  return std::isfinite(value) ? format_number(value) : "null";
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", ch);
          out += escaped;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m) {
  std::vector<TumPose> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) {
    poses.push_back({p.t_s, p.pose.mean.x(), p.pose.mean.y(), -depth_m, p.pose.mean.yaw()});
  }
  write_tum(path, poses);
}

void write_metrics_json(const std::string& path, const RunMetrics& m,
                        const std::string& dataset_dir) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "{\n"
        << "  \"method\": " << json_string(m.method) << ",\n"
        << "  \"truth\": " << json_string(m.truth) << ",\n"
        << "  \"dataset\": " << json_string(dataset_dir) << ",\n"
        << "  \"mean_error_m\": " << json_number(m.errors.mean_m) << ",\n"
        << "  \"rmse_m\": " << json_number(m.errors.rmse_m) << ",\n"
        << "  \"median_error_m\": " << json_number(m.errors.median_m) << ",\n"
        << "  \"max_error_m\": " << json_number(m.errors.max_m) << ",\n"
        << "  \"final_error_m\": " << json_number(m.errors.final_m) << ",\n"
        << "  \"truth_samples\": " << m.errors.count << ",\n"
        << "  \"segments\": {";
    for (std::size_t i = 0; i < m.segments.size(); ++i) {
      const auto& [name, mean] = m.segments[i];
      out << (i ? ", " : "") << json_string(name) << ": "
          << (mean ? json_number(*mean) : std::string("null"));
    }
    out << "},\n"
        << "  \"scans\": " << m.scans << ",\n"
        << "  \"matches_accepted\": " << m.matches_accepted << ",\n"
        << "  \"anees\": " << (m.anees ? json_number(*m.anees) : std::string("null")) << ",\n"
        << "  \"runtime_s\": " << json_number(m.runtime_s) << ",\n"
        << "  \"diagnostics\": {";
    for (std::size_t i = 0; i < m.diagnostics.size(); ++i) {
      out << (i ? ", " : "") << json_string(m.diagnostics[i].first) << ": "
          << json_number(m.diagnostics[i].second);
    }
    out << "}\n}\n";
  });
}

void write_scans_csv(const std::string& path, const std::vector<PlacedScan>& scans) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text =
        "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n";
    for (const PlacedScan& s : scans) {
      const GaussianPose2& pose = s.centre_world.pose;
      const Eigen::Matrix3d& P = pose.cov;
      for (const double v : {s.scan.t_s, pose.mean.x(), pose.mean.y(), pose.mean.yaw(), P(0, 0),
                             P(0, 1), P(0, 2), P(1, 1), P(1, 2), P(2, 2)}) {
        append_number(text, v);
        text += ',';
      }
      text += std::to_string(s.scan.points.size()) + "\n";
    }
    out << text;
  });
}

void write_points_ply(const std::string& path, const std::vector<Eigen::Vector2d>& points_m) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "ply\nformat ascii 1.0\ncomment msislab scan points, world frame (m)\n";
    text += "element vertex " + std::to_string(points_m.size()) +
            "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
    for (const Eigen::Vector2d& p : points_m) {
      append_number(text, p.x());
      text += ' ';
      append_number(text, p.y());
      text += " 0\n";
    }
    out << text;
  });
}

}  // namespace msislab::io
