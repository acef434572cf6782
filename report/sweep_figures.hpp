// The figures of a sweep directory (`msislab plot SWEEP_DIR`): a metric of its cells against one
// swept key.
#pragma once

#include <cstddef>
#include <string>

#include "plot/chart.hpp"
#include "report/method_styles.hpp"
#include "results/sweep_files.hpp"

namespace msislab::report {

/// Whether any row has a value of the metric (the figures drawn are those with data).
bool sweep_has_metric(const results::SweepTable& table, const std::string& metric);

/// A sweep: a metric of the cells against one swept key, one line per method and per value of the
/// other keys: "mean_error" with its 5-95 % band over the runs' mean errors, "anees",
/// "paired_difference" (each method's per-run mean error minus the first method's, with its 95 %
/// interval) or "linearisation" (epsilon of the match update, the inversion and the pose read-out:
/// a line per method and kind, log axis). Numeric values are placed at their value, others at
/// their rank (named in the title). std::invalid_argument for another metric.
plot::ChartSpec sweep_chart(const MethodStyles& styles, const results::SweepTable& table,
                            std::size_t key, const std::string& metric, int width_px,
                            int height_px);

}  // namespace msislab::report
