// The charts of `msislab plot`, built as plain plot::ChartSpec from the loaded results: a method
// against the truth on the map, position error against time, and Monte Carlo NEES per scan.
#pragma once

#include <string>
#include <vector>

#include "plot/chart.hpp"
#include "report/method_styles.hpp"
#include "report/plot_inputs.hpp"

namespace msislab::report {

/// The colour scaled towards black by `factor` (ellipses stand apart from their trajectory, a
/// method's further lines are darker shades).
std::uint32_t darker(std::uint32_t rgb, double factor);
/// An empty chart with its axis labels and size.
plot::ChartSpec empty_chart(const std::string& x_label, const std::string& y_label, int width_px,
                            int height_px);

/// Truth (or GPS) and the estimate in the world frame with equal aspect, the map points as small
/// dots and the 2-sigma position ellipses of every k-th scan (k = every, or about 25 in all).
plot::ChartSpec trajectory_chart(const MethodStyles& styles, const ResultData& result,
                                 int ellipse_every, int width_px, int height_px);

/// Position error against time since the first truth stamp, one line per result with errors.
plot::ChartSpec error_chart(const MethodStyles& styles,
                            const std::vector<const ResultData*>& results, int width_px,
                            int height_px);

/// Monte Carlo: the position error against time per method, its mean over the runs (in the
/// method's style) and the 5 and 95 % quantiles (dotted).
plot::ChartSpec error_spread_chart(const MethodStyles& styles,
                                   const std::vector<results::ErrorSpreadRow>& rows, int width_px,
                                   int height_px);

/// Monte Carlo: the distribution of the position error per method (every run's samples pooled),
/// as a histogram outline on shared bins.
plot::ChartSpec error_distribution_chart(const MethodStyles& styles,
                                         const std::vector<ErrorHistogram>& histograms,
                                         int width_px, int height_px);

/// Run-averaged NEES against scan index per method, with the 95% bounds; log y axis.
plot::ChartSpec nees_chart(const MethodStyles& styles, const std::vector<results::NeesRow>& rows,
                           int width_px, int height_px);

}  // namespace msislab::report
