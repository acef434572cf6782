// `msislab plot DIR`: (re)draws the figures of a result, comparison or Monte Carlo directory as PNG
// into DIR/figures/ (docs/cli.md lists them). Reading is separate from drawing: every input is
// checked before the first figure is written, and only drawing needs an X display (VTK).
#pragma once

#include <string>
#include <vector>

#include "report/method_styles.hpp"
#include "report/plot_inputs.hpp"

namespace msislab::app {

/// Draws every figure the inputs allow, the methods shown as `styles` say, and returns the files
/// written, in order. Needs an X display (plot/display.hpp).
std::vector<std::string> draw_plot(const report::PlotInputs& inputs,
                                   const report::MethodStyles& styles);

/// load_plot_inputs, then draw_plot (by default with the built-in methods' styles).
std::vector<std::string> plot(const report::PlotOptions& options,
                              const report::MethodStyles& styles = {});

}  // namespace msislab::app
