// The expectations file of `msislab check` (docs/formats.md, "Expectations file"): a list of
// stated expectations on result figures, read strictly (an unknown key, a wrong type or a
// contradiction is an InputError "FILE:LINE: key ...: what").
#pragma once

#include <string>
#include <vector>

#include "eval/expectations.hpp"

namespace msislab::settings {

/// Reads an expectations file. Each entry names its figure and at least one check; names are
/// unique (an entry without a name is named from its result, method and metric).
std::vector<Expectation> read_expectations_yaml(const std::string& path);

}  // namespace msislab::settings
