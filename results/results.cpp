#include "results/results.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/json.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "results/eval_scores_json.hpp"

namespace msislab::results {

void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m) {
  std::vector<io::TumPose> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) {
    poses.push_back({p.t_s, p.pose.mean.x(), p.pose.mean.y(), -depth_m, p.pose.mean.yaw()});
  }
  io::write_tum(path, poses);
}

void to_json(io::Json& json, const StoredMetrics& stored) {
  const RunMetrics& m = stored.metrics;
  json = io::Json::object();
  json["method"] = m.method;
  json["truth"] = m.truth;
  if (!stored.truth_file.empty()) json["truth_file"] = stored.truth_file;
  json["dataset"] = stored.dataset_dir.empty() ? io::Json() : io::Json(stored.dataset_dir);
  json["mean_error_m"] = m.errors.mean_m;
  json["rmse_m"] = m.errors.rmse_m;
  json["median_error_m"] = m.errors.median_m;
  json["max_error_m"] = m.errors.max_m;
  json["final_error_m"] = m.errors.final_m;
  json["truth_samples"] = m.errors.count;
  io::Json& segments = json["segments"] = io::Json::object();
  for (const auto& [name, mean] : m.segments) segments[name] = mean ? io::Json(*mean) : io::Json();
  io::Json& windows = json["segment_windows"] = io::Json::object();
  for (const TimeSegment& w : m.segment_windows) windows[w.name] = {w.begin_s, w.end_s};
  json["scans"] = m.scans;
  json["matches_accepted"] = m.matches_accepted;
  json["anees"] = m.anees ? io::Json(*m.anees) : io::Json();
  json["runtime_s"] = m.runtime_s;
  io::Json& diagnostics = json["diagnostics"] = io::Json::object();
  for (const auto& [name, value] : m.diagnostics) diagnostics[name] = value;
  if (m.eval_scores) add_eval_scores(json, *m.eval_scores);
}

void write_metrics_json(const std::string& path, const RunMetrics& metrics,
                        const std::string& dataset_dir, const std::string& truth_file) {
  io::write_json_file(path, StoredMetrics{metrics, dataset_dir, truth_file});
}

void write_scans_csv(const std::string& path, const std::vector<PlacedScan>& scans) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text =
        "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n";
    for (const PlacedScan& s : scans) {
      const GaussianPose2& pose = s.centre_world.pose;
      const Eigen::Matrix3d& P = pose.cov;
      for (const double v : {s.scan.t_s, pose.mean.x(), pose.mean.y(), pose.mean.yaw(), P(0, 0),
                             P(0, 1), P(0, 2), P(1, 1), P(1, 2), P(2, 2)}) {
        io::append_number(text, v);
        text += ',';
      }
      text += std::to_string(s.scan.points.size()) + "\n";
    }
    out << text;
  });
}

void write_calibration_csv(const std::string& path,
                           const std::vector<CalibrationSnapshot>& snapshots) {
  if (snapshots.empty()) throw std::invalid_argument("write_calibration_csv: no snapshot");
  const std::vector<CalibrationEstimate>& first = snapshots.front().estimates;
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "t_s";
    for (const CalibrationEstimate& c : first) text += ',' + c.name + ',' + c.name + "_sigma";
    text += '\n';
    for (const CalibrationSnapshot& s : snapshots) {
      if (s.estimates.size() != first.size()) {
        throw std::invalid_argument("write_calibration_csv: the parameters changed");
      }
      io::append_number(text, s.t_s);
      for (std::size_t i = 0; i < first.size(); ++i) {
        if (s.estimates[i].name != first[i].name) {
          throw std::invalid_argument("write_calibration_csv: the parameters changed");
        }
        text += ',';
        io::append_number(text, s.estimates[i].value);
        text += ',';
        io::append_number(text, s.estimates[i].sigma);
      }
      text += '\n';
    }
    out << text;
  });
}

void write_matches_csv(const std::string& path, const std::vector<MatchRow>& rows) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text =
        "t_s,scan,reference,t_reference_s,distance_m,outcome,observed,restarts,nis,z_x_m,z_y_m,"
        "z_yaw_rad,z_cov_xx,z_cov_xy,z_cov_xyaw,z_cov_yy,z_cov_yyaw,z_cov_yawyaw,pred_x_m,"
        "pred_y_m,pred_yaw_rad,pred_cov_xx,pred_cov_xy,pred_cov_xyaw,pred_cov_yy,pred_cov_yyaw,"
        "pred_cov_yawyaw,true_x_m,true_y_m,true_yaw_rad,nees\n";
    const auto field = [&text](double value, char end = ',') {
      if (std::isfinite(value)) io::append_number(text, value);
      text += end;
    };
    const auto gaussian = [&field](const GaussianPose2& g) {
      const Eigen::Matrix3d& P = g.cov;
      for (const double v : {g.mean.x(), g.mean.y(), g.mean.yaw(), P(0, 0), P(0, 1), P(0, 2),
                             P(1, 1), P(1, 2), P(2, 2)}) {
        field(v);
      }
    };
    for (const MatchRow& row : rows) {
      const MatchRecord& m = row.record;
      field(row.t_s);
      text += std::to_string(m.scan) + ',' + std::to_string(m.reference) + ',';
      field(row.t_reference_s);
      field(m.distance_m);
      text += (m.rejection == MatchRejection::kNone ? std::string("accepted")
                                                    : rejection_name(m.rejection)) +
              ',' + std::to_string(m.observed.rows()) + ',' + std::to_string(m.restarts) + ',';
      field(m.nis);
      gaussian(m.z);
      gaussian(m.predicted);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      field(row.has_truth ? row.truth.x() : nan);
      field(row.has_truth ? row.truth.y() : nan);
      field(row.has_truth ? row.truth.yaw() : nan);
      field(row.has_truth && m.valid ? row.nees : nan, '\n');
    }
    out << text;
  });
}

namespace {

double number_or_nan(const io::JsonObject& object, const std::string& key) {
  return object.number_or_null(key).value_or(std::numeric_limits<double>::quiet_NaN());
}

int count_of(const io::JsonObject& object, const std::string& key) {
  return static_cast<int>(object.integer(key, 0, std::numeric_limits<int>::max()));
}

std::vector<TimeSegment> read_segment_windows(const io::JsonObject& windows) {
  std::vector<TimeSegment> segments;
  for (const auto& [name, value] : windows.value().items()) {
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
      windows.fail(name, "expected [begin_s, end_s]");
    }
    segments.push_back({name, value[0].get<double>(), value[1].get<double>()});
  }
  return segments;
}

}  // namespace

void from_json(const io::JsonObject& json, StoredMetrics& stored) {
  RunMetrics& m = stored.metrics;
  m.method = json.string("method");
  m.truth = json.string("truth");
  if (json.has("truth_file")) stored.truth_file = json.string("truth_file");
  stored.dataset_dir = json.string_or_null("dataset").value_or("");
  m.errors.mean_m = json.number("mean_error_m");
  m.errors.rmse_m = json.number("rmse_m");
  m.errors.median_m = json.number("median_error_m");
  m.errors.max_m = json.number("max_error_m");
  m.errors.final_m = json.number("final_error_m");
  m.errors.count = static_cast<std::size_t>(count_of(json, "truth_samples"));
  const io::JsonObject segments = json.object("segments");
  for (const auto& [name, value] : segments.value().items()) {
    m.segments.emplace_back(name, segments.number_or_null(name));
  }
  if (json.has("segment_windows")) {
    m.segment_windows = read_segment_windows(json.object("segment_windows"));
  }
  m.scans = count_of(json, "scans");
  m.matches_accepted = count_of(json, "matches_accepted");
  m.anees = json.number_or_null("anees");
  m.runtime_s = number_or_nan(json, "runtime_s");
  const io::JsonObject diagnostics = json.object("diagnostics");
  for (const auto& [name, value] : diagnostics.value().items()) {
    m.diagnostics.emplace_back(name, number_or_nan(diagnostics, name));
  }
  m.eval_scores = read_eval_scores(json);
}

StoredMetrics read_metrics_json(const std::string& path) {
  return io::read_json_file_as<StoredMetrics>(path);
}

namespace {

// A number that may be nan or inf (a NEES of a singular covariance).
double parse_any_number(std::string_view token, const io::FieldAt& at) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) {
    io::fail_field(at, token, "is not a number");
  }
  return value;
}

}  // namespace

std::vector<StampedPose> read_scans_csv(const std::string& path) {
  static const char* const kColumns[] = {"t_s",      "x_m",        "y_m",      "yaw_rad",
                                         "cov_xx",   "cov_xy",     "cov_xyaw", "cov_yy",
                                         "cov_yyaw", "cov_yawyaw", "points"};
  std::vector<StampedPose> scans;
  io::for_each_csv_row(
      path, "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points",
      [&](std::string_view row, std::size_t line) {
        const auto fields = io::split_csv<11>(row, path, line);
        double v[10];
        for (std::size_t i = 0; i < 10; ++i)
          v[i] = io::parse_finite(fields[i], {path, line, i + 1, kColumns[i]});
        io::parse_integer(fields[10], {path, line, 11, kColumns[10]});
        if (!scans.empty() && v[0] < scans.back().t_s) {
          io::fail_at(path, line,
                      "t_s goes backwards (" + io::format_number(v[0]) + " after " +
                          io::format_number(scans.back().t_s) + ")");
        }
        StampedPose scan;
        scan.t_s = v[0];
        scan.pose.mean = Pose2(v[1], v[2], v[3]);
        scan.pose.cov << v[4], v[5], v[6], v[5], v[7], v[8], v[6], v[8], v[9];
        scans.push_back(scan);
      });
  return scans;
}

void write_nees_csv(const std::string& path, const std::vector<NeesSample>& samples) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "scan,t_s,nees\n";
    for (std::size_t i = 0; i < samples.size(); ++i) {
      text += std::to_string(i) + ',';
      io::append_number(text, samples[i].t_s);
      text += ',';
      io::append_number(text, samples[i].nees);
      text += '\n';
    }
    out << text;
  });
}

void write_errors_csv(const std::string& path, const std::vector<ErrorSample>& errors,
                      double t_first_truth_s) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "t_s,error_m\n";
    double next_s = 0.0;
    for (const ErrorSample& e : errors) {
      const double t_s = e.t_s - t_first_truth_s;
      if (t_s + 1e-9 < next_s) continue;
      io::append_number(text, t_s);
      text += ',';
      io::append_number(text, e.error_m);
      text += '\n';
      next_s = std::floor(t_s + 1e-9) + 1.0;
    }
    out << text;
  });
}

std::vector<ErrorSample> read_errors_csv(const std::string& path) {
  std::vector<ErrorSample> errors;
  io::for_each_csv_row(path, "t_s,error_m", [&](std::string_view row, std::size_t line) {
    const auto fields = io::split_csv<2>(row, path, line);
    const ErrorSample e{io::parse_finite(fields[0], {path, line, 1, "t_s"}),
                        io::parse_finite(fields[1], {path, line, 2, "error_m"})};
    if (!errors.empty() && !(e.t_s > errors.back().t_s)) {
      io::fail_at(path, line, "t_s does not increase");
    }
    errors.push_back(e);
  });
  return errors;
}

std::vector<NeesSample> read_nees_csv(const std::string& path) {
  std::vector<NeesSample> samples;
  io::for_each_csv_row(path, "scan,t_s,nees", [&](std::string_view row, std::size_t line) {
    const auto fields = io::split_csv<3>(row, path, line);
    const std::int64_t scan = io::parse_integer(fields[0], {path, line, 1, "scan"});
    if (scan != static_cast<std::int64_t>(samples.size())) {
      io::fail_at(path, line,
                  "scan " + std::to_string(scan) + " out of order (expected " +
                      std::to_string(samples.size()) + ")");
    }
    samples.push_back({io::parse_finite(fields[1], {path, line, 2, "t_s"}),
                       parse_any_number(fields[2], {path, line, 3, "nees"})});
  });
  return samples;
}

void write_points_ply(const std::string& path, const std::vector<Eigen::Vector2d>& points_m) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "ply\nformat ascii 1.0\ncomment msislab scan points, world frame (m)\n";
    text += "element vertex " + std::to_string(points_m.size()) +
            "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
    for (const Eigen::Vector2d& p : points_m) {
      io::append_number(text, p.x());
      text += ' ';
      io::append_number(text, p.y());
      text += " 0\n";
    }
    out << text;
  });
}

}  // namespace msislab::results
