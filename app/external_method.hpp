// An external method (a program declared in a methods file, docs/formats.md) run on a dataset
// directory: its command with the placeholders filled in, run by app/external_program, then its
// trajectory.tum (and scans.csv when it wrote one) read from its output folder and scored against
// the dataset's truth exactly as a built-in method's estimate.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/method_catalogue.hpp"
#include "app/run_method.hpp"

namespace msislab::app {

/// Where an external method runs.
struct ExternalSetup {
  std::string dataset_dir;  ///< {dataset}: the dataset directory (on disk)
  std::string config_path;  ///< {config}: a SLAM config YAML file
  std::uint64_t seed = 0;   ///< {seed}
  /// A folder of msislab's: made afresh, it holds {out} (WORK/out) and the program's stderr
  /// (WORK/stderr.log); the caller removes it.
  std::string work_dir;
};

/// The method did not give a result: it could not start, exited non-zero, ran past its time
/// limit, or left no readable trajectory. `stderr_tail` holds its last stderr lines.
class ExternalMethodError : public std::runtime_error {
 public:
  ExternalMethodError(const std::string& reason, std::vector<std::string> stderr_tail)
      : std::runtime_error(reason), stderr_tail_(std::move(stderr_tail)) {}
  const std::vector<std::string>& stderr_tail() const { return stderr_tail_; }

 private:
  std::vector<std::string> stderr_tail_;
};

/// How many of the program's last stderr lines a failure keeps.
inline constexpr std::size_t kStderrTailLines = 20;

/// Runs the method's program and scores what it wrote, as run_method does for a built-in method
/// (`in` is the same dataset, read by msislab: its truth, config and start). Throws
/// ExternalMethodError.
MethodResult run_external_method(const Method& method, const dataset::RunInputs& in,
                                 const ExternalSetup& setup);

}  // namespace msislab::app
