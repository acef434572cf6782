#include <cmath>
#include <sstream>

#include "report/method_styles.hpp"
#include "report/results_markdown.hpp"

namespace msislab::report {

namespace {

/// A change above this share of the default's error is a cliff, shown in bold (docs/results.md,
/// "How far the real result can be trusted").
constexpr double kCliffShare = 0.25;

/// "2.84 (+64 %)", bold when the change is a cliff.
std::string moved_error(double error_m, double default_m, bool& cliff) {
  if (!(default_m > 0.0)) return fixed(error_m, 2);  // no change to speak of against 0 m
  const double change = error_m / default_m - 1.0;
  const double percent = std::round(100.0 * change);
  std::ostringstream cell;
  const bool big = std::abs(change) > kCliffShare;
  cliff |= big;
  cell << (big ? "**" : "") << fixed(error_m, 2) << " (" << (percent > 0.0 ? "+" : "")
       << fixed(percent == 0.0 ? 0.0 : percent, 0) << " %)" << (big ? "**" : "");
  return cell.str();
}

}  // namespace

void sensitivity_section(const MethodStyles& styles, std::ostringstream& md,
                         const std::string& source, const std::vector<io::SensitivityRow>& rows) {
  md << "\n## How far the real result can be trusted\n\n"
     << "`" << source << "` (`tools/real_sensitivity.sh`): the real St. Pere run with each "
     << "parameter of the front end and back end that the default config sets moved down and up "
     << "(by 10 %; an integer by one step, a probability's complement by 10 %), one at a time; "
     << "the mean error against the GPS track (the pose graph's smoothed trajectory for its own "
     << "parameters). A report of how much one real figure depends on each number, never a way "
     << "to choose one: parameters are chosen on simulation. In bold: a change of more than "
     << fixed(100.0 * kCliffShare, 0) << " % of the error at the default.\n\n"
     << "| parameter | default | method | mean error [m] | down: value | mean error [m] | up: "
        "value | mean error [m] |\n"
     << "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |\n";
  int cliffs = 0;
  for (const io::SensitivityRow& r : rows) {
    bool cliff = false;
    const std::string low = moved_error(r.low_mean_error_m, r.mean_error_m, cliff);
    const std::string high = moved_error(r.high_mean_error_m, r.mean_error_m, cliff);
    cliffs += cliff ? 1 : 0;
    md << "| `" << r.parameter << "` | " << r.default_value << " | " << styles.title(r.method)
       << " | " << fixed(r.mean_error_m, 2) << " | " << r.low_value << " | " << low << " | "
       << r.high_value << " | " << high << " |\n";
  }
  md << "\nParameters whose 10 % change moves the error by more than "
     << fixed(100.0 * kCliffShare, 0) << " %: " << cliffs << " of " << rows.size() << ".\n";
}

}  // namespace msislab::report
