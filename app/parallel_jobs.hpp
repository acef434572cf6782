// A small job pool for the Monte Carlo runs: job(i) for every index on a fixed number of threads,
// while the calling thread ticks (to redraw a progress line).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>

namespace msislab::app {

/// Calls job(i) for i = 0 .. count-1, each exactly once, on min(workers, count) threads, handing
/// out the indices in increasing order. The calling thread calls tick() every tick_period until
/// every job has returned. When a job throws, no further job starts and the first exception is
/// rethrown once the running ones have returned.
void run_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& job,
                  const std::function<void()>& tick = {},
                  std::chrono::milliseconds tick_period = std::chrono::milliseconds(1000));

}  // namespace msislab::app
