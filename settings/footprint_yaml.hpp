// The SLAM config's `footprint` section (docs/formats.md, "footprint"): the beam's footprint table
// that `msislab footprint` measures, held in the config itself so that a config that names a
// table carries it wherever it is copied (a Monte Carlo's or a sweep's inputs).
//
//   footprint:
//     ranges_m: [5, 10, ...]          # the grid's nodes, ascending
//     incidences_deg: [0, 15, ...]    # ascending, 0 to 90
//     min_samples: 20                 # a cell with fewer samples has no figure
//     rows:                           # one per range, one entry per incidence
//       - {offset_m: [...], sd_m: [...], samples: [...]}
//     line_radius_m: 3                # the lines the incidence is taken from
//     line_min_points: 3
//     line_max_eigen_ratio: 0.05
//
// A cell without a figure is written with offset and spread 0 and read as none (NaN).
#pragma once

#include <string>

#include "eval/footprint_calibration.hpp"
#include "io/yaml_fields.hpp"
#include "slam/beam_footprint.hpp"

namespace msislab::settings {

/// Reads the section into c (absent: c as it was). Bad input (unknown keys, rows that do not
/// match the grid, nodes out of order, a negative spread or count) is an io::InputError naming
/// the file and line. Calls map.finish().
void read_footprint_section(io::YamlMap map, FootprintConfig& c);

/// Whether the SLAM config file has a top-level `footprint` key (a config `msislab footprint`
/// writes its section after must have none: YAML allows a key once).
bool has_footprint_section(const std::string& config_path);

/// The section's text for an estimate (top-level key `footprint:`), `comment` (lines, each
/// written after "# ") first.
std::string footprint_section_yaml(const FootprintEstimate& estimate, int min_samples,
                                   const LineNormalConfig& line, const std::string& comment);

}  // namespace msislab::settings
