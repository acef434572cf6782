#include "app/worker_processes.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <map>

namespace msislab::app {

namespace {

constexpr int kUncaughtExceptionStatus = 70;  // EX_SOFTWARE

/// The worker's side of fork(): the caller's signal mask back, death with the caller, the job.
[[noreturn]] void be_worker(const WorkerPool& pool, std::size_t index, const sigset_t& old_mask,
                            pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);  // the caller died before prctl took hold
  ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  int status = 0;
  try {
    status = pool.job(index);
  } catch (const std::exception& e) {
    std::cerr << "msislab: worker: " << e.what() << std::endl;
    status = kUncaughtExceptionStatus;
  } catch (...) {
    std::cerr << "msislab: worker: unknown exception" << std::endl;
    status = kUncaughtExceptionStatus;
  }
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  // No atexit handlers or static destructors: they belong to the caller's process.
  ::_exit(status);
}

/// One call of run_worker_processes: the watched signals (blocked, so that they wait for
/// sigtimedwait instead of interrupting or ending the caller), the workers running and the next
/// job. Should a callback throw, the destructor still ends every worker and gives the caller its
/// signal mask back.
class WorkerRun {
 public:
  WorkerRun(std::size_t count, const WorkerPool& pool)
      : count_(count),
        pool_(pool),
        self_(::getpid()),
        workers_(static_cast<std::size_t>(std::max(1, pool.workers))) {
    sigemptyset(&watched_);
    for (const int sig : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&watched_, sig);
    ::pthread_sigmask(SIG_BLOCK, &watched_, &old_mask_);
  }
  ~WorkerRun() {
    for (const auto& [pid, index] : running_) ::kill(pid, SIGTERM);
    for (const auto& [pid, index] : running_) ::waitpid(pid, nullptr, 0);
    ::pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
  }
  WorkerRun(const WorkerRun&) = delete;
  WorkerRun& operator=(const WorkerRun&) = delete;

  /// Runs every job; 0, or the signal that stopped them.
  int run() {
    auto last_tick = std::chrono::steady_clock::now();
    while (true) {
      start_workers();
      if (running_.empty()) break;
      wait_for_signal();
      reap_finished();
      const auto now = std::chrono::steady_clock::now();
      if (pool_.tick && now - last_tick >= pool_.tick_period) {
        pool_.tick();
        last_tick = now;
      }
    }
    // A stop request (or children's ends) still pending is consumed here, not by the caller.
    timespec none{0, 0};
    for (int sig; (sig = ::sigtimedwait(&watched_, nullptr, &none)) > 0;) {
      if (stop_ == 0 && sig != SIGCHLD) stop_ = sig;
    }
    return stop_;
  }

 private:
  /// Forks workers for the next jobs, up to the pool's size, unless stopped.
  void start_workers() {
    while (stop_ == 0 && next_ < count_ && running_.size() < workers_) {
      std::cout.flush();
      std::cerr.flush();
      const pid_t pid = ::fork();
      if (pid == 0) be_worker(pool_, next_, old_mask_, self_);
      if (pid < 0) {
        // No process for it: recorded as a failure to start, and the pool goes on.
        ProcessResult failed;
        failed.start_error = "cannot start a worker process (fork failed)";
        if (pool_.finished) pool_.finished(next_, failed);
      } else {
        running_[pid] = next_;
      }
      ++next_;
    }
  }

  /// Waits up to a tick for a signal; a stop request ends every worker.
  void wait_for_signal() {
    const auto period_ms = pool_.tick_period.count();
    timespec timeout{static_cast<time_t>(period_ms / 1000),
                     static_cast<long>((period_ms % 1000) * 1000000)};
    const int sig = ::sigtimedwait(&watched_, nullptr, &timeout);
    if ((sig == SIGINT || sig == SIGTERM || sig == SIGHUP) && stop_ == 0) {
      stop_ = sig;
      for (const auto& [pid, index] : running_) ::kill(pid, SIGTERM);
    }
  }

  /// Collects the workers that ended: finished, or stopped (killed by the stop request).
  void reap_finished() {
    for (auto it = running_.begin(); it != running_.end();) {
      int status = 0;
      if (::waitpid(it->first, &status, WNOHANG) != it->first) {
        ++it;
        continue;
      }
      const ProcessResult result = process_result(status);
      if (stop_ != 0 && !result.exited) {
        if (pool_.stopped) pool_.stopped(it->second);
      } else if (pool_.finished) {
        pool_.finished(it->second, result);
      }
      it = running_.erase(it);
    }
  }

  std::size_t count_;
  const WorkerPool& pool_;
  pid_t self_;
  std::size_t workers_;
  sigset_t watched_{};
  sigset_t old_mask_{};
  std::map<pid_t, std::size_t> running_;
  std::size_t next_ = 0;
  int stop_ = 0;
};

}  // namespace

int run_worker_processes(std::size_t count, const WorkerPool& pool) {
  return WorkerRun(count, pool).run();  // the mask is restored by ~WorkerRun
}

}  // namespace msislab::app
