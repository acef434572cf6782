#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "io/input_error.hpp"
#include "report/method_styles.hpp"
#include "report/results_markdown.hpp"

namespace msislab::report {

namespace fs = std::filesystem;

namespace {

std::string scientific(const std::optional<double>& value) {
  if (!value) return "n/a";
  std::ostringstream out;
  out << std::setprecision(1) << std::scientific << *value;
  return out.str();
}

/// Metres in millimetres, one decimal, without a "-0.0".
std::string millimetres(double metres) {
  const std::string text = fixed(1000.0 * metres, 1);
  return text == "-0.0" ? "0.0" : text;
}

/// The shape of a sweep's table: its methods and cells in order of appearance, and whether the
/// linearisation errors were measured.
struct SweepShape {
  const results::SweepTable& table;
  std::vector<std::string> methods;
  std::vector<int> cells;
  bool linearisation = false;

  const results::SweepRow* row(int cell, const std::string& method) const {
    for (const results::SweepRow& r : table.rows) {
      if (r.cell == cell && r.method == method) return &r;
    }
    return nullptr;
  }
};

SweepShape shape_of(const SweepFolder& sweep) {
  SweepShape shape{sweep.table, {}, {}, false};
  for (const results::SweepRow& r : sweep.table.rows) {
    if (std::find(shape.methods.begin(), shape.methods.end(), r.method) == shape.methods.end())
      shape.methods.push_back(r.method);
    if (std::find(shape.cells.begin(), shape.cells.end(), r.cell) == shape.cells.end())
      shape.cells.push_back(r.cell);
    shape.linearisation |= r.linearisation_pose.has_value();
  }
  if (shape.methods.empty()) {
    io::fail_file(sweep.dir + "/sweep.csv", "no rows (the sweep has not run)");
  }
  return shape;
}

/// The title, the paragraph and the table's header and rule.
void sweep_header(const MethodStyles& styles, std::ostringstream& md, const SweepFolder& sweep,
                  const SweepShape& shape) {
  const std::vector<std::string>& methods = shape.methods;
  const std::string name = fs::path(sweep.dir).lexically_normal().filename().string();
  md << "\n## Sweep: `" << name << "`\n\n"
     << "`" << sweep.dir << "/sweep.csv`, " << shape.cells.size()
     << " cells. Mean error over the runs; the paired difference is each run's mean error minus "
     << styles.title(methods.front())
     << "'s on the same simulated data, averaged, with its 95 % interval (docs/formats.md)"
     << (shape.linearisation ? "; epsilon is the linearisation error (docs/robocentric.md)" : "")
     << ".\n\n|";
  std::string rule = "|";
  for (const std::string& key : shape.table.keys) {
    md << " " << key.substr(key.rfind('.') + 1) << " |";
    rule += " ---: |";
  }
  for (const std::string& m : methods) {
    md << " " << styles.title(m) << " [m] |";
    rule += " ---: |";
  }
  for (std::size_t i = 1; i < methods.size(); ++i) {
    md << " " << styles.title(methods[i]) << " minus " << styles.title(methods.front())
       << " [mm] |";
    rule += " ---: |";
  }
  md << " ANEES |";
  rule += " ---: |";
  if (shape.linearisation) {
    md << " epsilon: match update | inversion | pose read-out |";
    rule += " ---: | ---: | ---: |";
  }
  md << "\n" << rule << "\n";
}

/// One cell's row; the cells whose paired difference is beyond the noise are added to `beyond`.
void sweep_row(std::ostringstream& md, const SweepShape& shape, int cell,
               std::vector<std::string>& beyond) {
  const std::vector<std::string>& methods = shape.methods;
  const results::SweepRow* first = shape.row(cell, methods.front());
  md << "|";
  for (std::size_t k = 0; k < shape.table.keys.size(); ++k) {
    md << " " << (first ? first->values[k] : "") << " |";
  }
  std::string anees, match, inversion, pose;
  for (const std::string& m : methods) {
    const results::SweepRow* r = shape.row(cell, m);
    md << " " << (r ? fixed(r->mean_error_m, 3) : "n/a") << " |";
    const std::string sep = m == methods.front() ? "" : " / ";
    anees += sep + (r ? fixed(r->anees, 2) : "n/a");
    if (!r) continue;
    match += sep + scientific(r->linearisation_observation);
    pose += sep + scientific(r->linearisation_pose);
    if (r->linearisation_inversion) {
      inversion += (inversion.empty() ? "" : " / ") + scientific(r->linearisation_inversion);
    }
  }
  for (std::size_t i = 1; i < methods.size(); ++i) {
    const results::SweepRow* r = shape.row(cell, methods[i]);
    if (!r || !r->paired_difference_m) {
      md << " n/a |";
      continue;
    }
    const bool significant = *r->paired_ci95_lower_m > 0.0 || *r->paired_ci95_upper_m < 0.0;
    md << " " << (significant ? "**" : "") << millimetres(*r->paired_difference_m) << " ["
       << millimetres(*r->paired_ci95_lower_m) << ", " << millimetres(*r->paired_ci95_upper_m)
       << "]" << (significant ? "**" : "") << " |";
    if (significant) beyond.push_back("cell " + std::to_string(cell) + " (" + methods[i] + ")");
  }
  md << " " << anees << " |";
  if (shape.linearisation) {
    md << " " << match << " | " << (inversion.empty() ? "n/a" : inversion) << " | " << pose << " |";
  }
  md << "\n";
}

}  // namespace

void sweep_section(const MethodStyles& styles, std::ostringstream& md, const SweepFolder& sweep) {
  const SweepShape shape = shape_of(sweep);
  sweep_header(styles, md, sweep, shape);
  std::vector<std::string> beyond;
  for (const int cell : shape.cells) sweep_row(md, shape, cell, beyond);
  md << "\nPaired differences beyond the Monte Carlo noise (95 % interval without 0, in bold): ";
  if (beyond.empty()) {
    md << "none.\n";
  } else {
    for (std::size_t i = 0; i < beyond.size(); ++i) md << (i ? ", " : "") << beyond[i];
    md << ".\n";
  }
}

}  // namespace msislab::report
