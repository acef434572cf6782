// The progress of a batch of runs: on a terminal a bar redrawn in place with \r, otherwise one
// plain line per finished run, "montecarlo: 12/50 runs done, 0 failed, elapsed 1m02s, eta 3m10s".
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <ostream>
#include <string>

namespace msislab::app {

/// "45s", "1m02s", "2h05m".
std::string format_duration(double seconds);

class Progress {
 public:
  /// `total` runs, of which `already_done` were finished before this session (they do not count
  /// for the ETA).
  Progress(std::size_t total, std::size_t already_done, bool terminal, std::ostream& out);

  /// A run of this session finished (failed: at least one method failed). Thread-safe.
  void run_finished(bool failed);
  /// Terminal: redraws the line (the elapsed time moves on). Thread-safe.
  void redraw();
  /// Terminal: ends the line.
  void end();

  /// The text of the progress line, without the bar.
  std::string line() const;

 private:
  void draw_locked();
  std::string line_locked() const;

  mutable std::mutex mutex_;
  std::size_t total_, already_done_, done_, failed_ = 0;
  bool terminal_;
  std::ostream& out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace msislab::app
