#include "dataset/navigation_data.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "dataset/dataset.hpp"
#include "dataset/truth.hpp"
#include "geometry/angles.hpp"
#include "geometry/se2.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::dataset {

NavigationData load_navigation_data(const std::string& dataset_dir) {
  NavigationData data;
  const DatasetFiles files = find_dataset_files(dataset_dir);
  const Calibration calibration = load_calibration(files);
  data.navigation = load_navigation(files, calibration);
  data.p_vehicle_dvl_m = {calibration.dvl.x_m, calibration.dvl.y_m};
  const std::vector<io::DvlRecord> records = io::read_dvl_log(*files.dvl);
  const bool has_compass = std::any_of(records.begin(), records.end(),
                                       [](const io::DvlRecord& r) { return r.heading_deg != 0.0; });
  for (const io::DvlRecord& r : records) {
    DvlRow row{r.t_log_s, r.bottom_vel_status == 1.0, std::nullopt};
    if (has_compass) row.compass_yaw_rad = normalize_angle(M_PI / 2 - r.heading_deg / kRadToDeg);
    data.dvl_rows.push_back(row);
  }
  if (files.gps) data.gps = load_gps_fixes(files, calibration);
  const Truth truth = load_truth(files, calibration);
  data.truth = truth.positions;
  data.truth_kind = truth.kind;
  return data;
}

}  // namespace msislab::dataset
