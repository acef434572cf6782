// The logs behind the navigation statistics (eval/navigation_statistics.hpp), read from a dataset
// directory, real or simulated.
#pragma once

#include <string>

#include "eval/navigation_statistics.hpp"

namespace msislab::dataset {

/// Reads a dataset directory (real or simulated) through io/. Throws io::InputError.
NavigationData load_navigation_data(const std::string& dataset_dir);

}  // namespace msislab::dataset
