#include "app/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace msislab::app {

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s < 60) {
    std::snprintf(text, sizeof(text), "%lds", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof(text), "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof(text), "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  }
  return text;
}

Progress::Progress(std::size_t total, std::size_t already_done, bool terminal, std::ostream& out)
    : total_(total),
      already_done_(already_done),
      done_(already_done),
      terminal_(terminal),
      out_(out) {}

void Progress::run_finished(bool failed) {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  failed_ += failed;
  draw_locked();
}

void Progress::redraw() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_) draw_locked();
}

void Progress::end() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_) out_ << std::endl;
}

std::string Progress::line() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return line_locked();
}

std::string Progress::line_locked() const {
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t executed = done_ - already_done_;
  std::string eta = "?";
  if (done_ >= total_) {
    eta = "0s";
  } else if (executed > 0) {
    eta = format_duration(elapsed_s / static_cast<double>(executed) *
                          static_cast<double>(total_ - done_));
  }
  return "montecarlo: " + std::to_string(done_) + "/" + std::to_string(total_) + " runs done, " +
         std::to_string(failed_) + " failed, elapsed " + format_duration(elapsed_s) + ", eta " +
         eta;
}

void Progress::draw_locked() {
  if (!terminal_) {
    out_ << line_locked() << std::endl;
    return;
  }
  constexpr std::size_t kWidth = 30;
  const std::size_t filled = total_ ? kWidth * done_ / total_ : kWidth;
  // The \x1b[K clears what a longer earlier line left.
  out_ << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] "
       << line_locked() << "\x1b[K" << std::flush;
}

}  // namespace msislab::app
