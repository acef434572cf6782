// Jobs in forked worker processes, for the Monte Carlo runs: a job that crashes (a signal, an
// abort) takes down its own process only, and a stop request (SIGINT, SIGTERM, SIGHUP) stops
// every worker before the call returns, so none is left behind.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>

#include "app/process.hpp"

namespace msislab::app {

struct WorkerPool {
  int workers = 1;  ///< processes at once (at least 1)
  /// Runs in the worker process (forked from the caller) for job i; its return value is the
  /// worker's exit status. An exception escaping it exits the worker with status 70.
  std::function<int(std::size_t)> job;
  /// Runs in the calling process when job i's worker has ended, in the order they end.
  std::function<void(std::size_t, const ProcessResult&)> finished;
  /// Runs in the calling process about every tick_period while workers run.
  std::function<void()> tick;
  std::chrono::milliseconds tick_period{1000};
  /// Runs in the calling process for each job whose worker a stop request killed, once it has
  /// ended (to remove what it half wrote).
  std::function<void(std::size_t)> stopped;
};

/// Starts job(i) for i = 0 .. count-1 in increasing order, each in its own worker process, at
/// most pool.workers at a time, and waits for them. Returns 0 when every job ran, or the signal
/// number of the stop request (SIGINT, SIGTERM or SIGHUP) that ended the pool early: then every
/// running worker was sent SIGTERM and waited for, and no further job started.
///
/// Workers die with the caller (PR_SET_PDEATHSIG) should it be killed outright. The signal mask of
/// the calling thread is restored on return; the caller must be the only thread that forks.
int run_worker_processes(std::size_t count, const WorkerPool& pool);

}  // namespace msislab::app
