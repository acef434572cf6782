// The table tools/real_sensitivity.sh writes (`--csv`): one parameter of the SLAM config per row,
// moved down and up from its default, with the mean error of a run at each value. `msislab report
// --sensitivity` renders it (docs/results.md).
#pragma once

#include <string>
#include <vector>

namespace msislab::io {

struct SensitivityRow {
  std::string parameter;      ///< the config key, dotted ("trajectory_slam.innovation_gate_chi2")
  std::string default_value;  ///< as the script wrote it
  std::string method;         ///< the method scored
  double mean_error_m = 0.0;  ///< at the default
  std::string low_value;
  double low_mean_error_m = 0.0;
  std::string high_value;
  double high_mean_error_m = 0.0;
};

inline constexpr const char* kSensitivityHeader =
    "parameter,default,method,mean_error_m,low,low_mean_error_m,high,high_mean_error_m";

/// Reads the table; InputError naming the file and line for a wrong header, a short or long row or
/// a value that is not a finite number.
std::vector<SensitivityRow> read_sensitivity_csv(const std::string& path);

}  // namespace msislab::io
