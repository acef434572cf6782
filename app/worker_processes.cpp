#include "app/worker_processes.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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

}  // namespace

int run_worker_processes(std::size_t count, const WorkerPool& pool) {
  sigset_t watched, old_mask;
  sigemptyset(&watched);
  for (const int sig : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&watched, sig);
  // Blocked, they wait for sigtimedwait below instead of interrupting (or ending) the caller.
  ::pthread_sigmask(SIG_BLOCK, &watched, &old_mask);
  const pid_t self = ::getpid();
  const std::size_t workers = static_cast<std::size_t>(std::max(1, pool.workers));

  std::map<pid_t, std::size_t> running;
  // Should a callback throw, no worker outlives the call and the caller's mask comes back.
  struct Cleanup {
    std::map<pid_t, std::size_t>& running;
    const sigset_t& old_mask;
    ~Cleanup() {
      for (const auto& [pid, index] : running) ::kill(pid, SIGTERM);
      for (const auto& [pid, index] : running) ::waitpid(pid, nullptr, 0);
      ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
    }
  } cleanup{running, old_mask};
  std::size_t next = 0;
  int stop = 0;
  auto last_tick = std::chrono::steady_clock::now();
  while (true) {
    while (stop == 0 && next < count && running.size() < workers) {
      std::cout.flush();
      std::cerr.flush();
      const pid_t pid = ::fork();
      if (pid == 0) be_worker(pool, next, old_mask, self);
      if (pid < 0) {
        // No process for it: recorded as a failure to start, and the pool goes on.
        ProcessResult failed;
        failed.start_error = "cannot start a worker process (fork failed)";
        if (pool.finished) pool.finished(next, failed);
      } else {
        running[pid] = next;
      }
      ++next;
    }
    if (running.empty()) break;

    const auto period_ms = pool.tick_period.count();
    timespec timeout{static_cast<time_t>(period_ms / 1000),
                     static_cast<long>((period_ms % 1000) * 1000000)};
    const int sig = ::sigtimedwait(&watched, nullptr, &timeout);
    if ((sig == SIGINT || sig == SIGTERM || sig == SIGHUP) && stop == 0) {
      stop = sig;
      for (const auto& [pid, index] : running) ::kill(pid, SIGTERM);
    }
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      if (::waitpid(it->first, &status, WNOHANG) != it->first) {
        ++it;
        continue;
      }
      const ProcessResult result = process_result(status);
      if (stop != 0 && !result.exited) {
        if (pool.stopped) pool.stopped(it->second);
      } else if (pool.finished) {
        pool.finished(it->second, result);
      }
      it = running.erase(it);
    }
    const auto now = std::chrono::steady_clock::now();
    if (pool.tick && now - last_tick >= pool.tick_period) {
      pool.tick();
      last_tick = now;
    }
  }
  // A stop request (or children's ends) still pending is consumed here, not by the caller.
  timespec none{0, 0};
  for (int sig; (sig = ::sigtimedwait(&watched, nullptr, &none)) > 0;) {
    if (stop == 0 && sig != SIGCHLD) stop = sig;
  }
  return stop;  // the mask is restored by cleanup
}

}  // namespace msislab::app
