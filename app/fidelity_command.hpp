// `msislab fidelity REAL_DATASET SIM_DATASET [--out DIR]`: the simulator against the real sonar,
// statistic by statistic (docs/fidelity.md): both datasets' detections go through the same code,
// and the table gives the two values, their ratio and, for distributions, the KS distance. The
// datasets are read and compared, and the page built, by report/fidelity_report.hpp; this command
// checks the output folder first, then prints the table and writes the files and figures.
#pragma once

#include <string>
#include <vector>

#include "report/fidelity_report.hpp"

namespace msislab::app {

/// Writes DIR/fidelity.md, DIR/fidelity.json, DIR/figures/ranges.png and
/// DIR/figures/revolution.png into a scratch sibling folder that then replaces DIR; returns the
/// files. Needs an X display (plot/display.hpp).
std::vector<std::string> write_fidelity(const report::FidelityReport& compared);

}  // namespace msislab::app
