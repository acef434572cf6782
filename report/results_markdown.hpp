// The Markdown of `msislab report`'s page (report/results_page.hpp): Table I, the figure lists,
// a section per Monte Carlo directory (report/results_page.cpp), per sweep
// (report/results_sweep.cpp) and for the real result's sensitivity
// (report/results_sensitivity.cpp), and the cell formats they share.
#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "report/results_page.hpp"

namespace msislab::report {

/// A table cell: the value with `decimals` decimals, "n/a" when it is not finite or missing.
std::string fixed(double value, int decimals);
std::string fixed(const std::optional<double>& value, int decimals);
/// A fraction as a percentage with one decimal, "n/a" when missing.
std::string percent(const std::optional<double>& fraction);

/// A sweep's sweep.csv as a table: a row per cell, per method its mean error and ANEES, each
/// further method's paired difference to the first with its 95 % interval, and the linearisation
/// errors when measured; then the cells where the paired difference is beyond the noise.
void sweep_section(const MethodStyles& styles, std::ostringstream& md, const SweepFolder& sweep);

/// The real result's sensitivity (tools/real_sensitivity.sh): a row per parameter, its error
/// moved down and up with the change in percent, the parameters that move it by more than a
/// quarter in bold, and how many they are.
void sensitivity_section(const MethodStyles& styles, std::ostringstream& md,
                         const std::string& source, const std::vector<io::SensitivityRow>& rows);

}  // namespace msislab::report
