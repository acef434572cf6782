#include "app/navigation_data.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "app/truth.hpp"
#include "geometry/se2.hpp"
#include "io/dataset.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::app {

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;
}  // namespace

NavigationData load_navigation_data(const std::string& dataset_dir) {
  NavigationData data;
  const io::DatasetFiles files = io::find_dataset_files(dataset_dir);
  const Calibration calibration = io::load_calibration(files);
  data.navigation = io::load_navigation(files, calibration);
  data.p_vehicle_dvl_m = {calibration.dvl.x_m, calibration.dvl.y_m};
  const std::vector<io::DvlRecord> records = io::read_dvl_log(*files.dvl);
  const bool has_compass = std::any_of(records.begin(), records.end(),
                                       [](const io::DvlRecord& r) { return r.heading_deg != 0.0; });
  for (const io::DvlRecord& r : records) {
    DvlRow row{r.t_log_s, r.bottom_vel_status == 1.0, std::nullopt};
    if (has_compass) row.compass_yaw_rad = normalize_angle(M_PI / 2 - r.heading_deg / kRadToDeg);
    data.dvl_rows.push_back(row);
  }
  if (files.gps) data.gps = io::load_gps_fixes(files, calibration);
  const Truth truth = load_truth(files, calibration);
  data.truth = truth.positions;
  data.truth_kind = truth.kind;
  return data;
}

}  // namespace msislab::app
