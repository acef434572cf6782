// `msislab segment DATASET_DIR [--method M ...|all] [--threshold T] [--min-range R] [--out FILE]`:
// scores beam segmentation of a simulated dataset's *_IS.log against truth/beams.csv
// (docs/front_end.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/beam_segmentation.hpp"
#include "slam/segmentation_score.hpp"

namespace msislab::app {

struct SegmentOptions {
  std::string dataset_dir;
  std::vector<std::string> methods;   ///< method names or "all"; empty means all
  std::optional<double> threshold;    ///< overrides the default config's threshold
  std::optional<double> min_range_m;  ///< overrides the default config's minimum range
  std::string out_path;               ///< Markdown copy of the table; empty: none
};

struct SegmentRow {
  SegmentationConfig config;
  SegmentationScore score;
};

struct SegmentReport {
  std::vector<SegmentRow> rows;
  std::string markdown;  ///< the table and a line saying what it counts
};

/// Reads the IS log and the beam truth, scores every requested method and writes --out when given.
/// Throws io::InputError on bad input: unknown method, no *_IS.log or truth/beams.csv, beam counts
/// that differ, malformed files.
SegmentReport segment(const SegmentOptions& options);

/// The Markdown table of the rows, then a line saying what each column counts.
std::string segmentation_markdown(const std::vector<SegmentRow>& rows);

}  // namespace msislab::app
