#include "app/external_program.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

extern char** environ;

namespace msislab::app {

namespace {

using Clock = std::chrono::steady_clock;

/// This process's environment with the spec's variables set.
std::vector<std::string> environment_of(const ProgramSpec& spec) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    bool replaced = false;
    for (const auto& [name, value] : spec.environment) {
      replaced |= entry.rfind(name + "=", 0) == 0;
    }
    if (!replaced) env.push_back(entry);
  }
  for (const auto& [name, value] : spec.environment) env.push_back(name + "=" + value);
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& texts) {
  std::vector<char*> p;
  for (std::string& t : texts) p.push_back(t.data());
  p.push_back(nullptr);
  return p;
}

/// The child's side of fork(): its own group, death with this process, the signals back to
/// their defaults, the files, then the program. Only async-signal-safe calls.
[[noreturn]] void be_program(const ProgramSpec& spec, char* const* argv, char* const* envp,
                             int stderr_fd, int status_fd, pid_t parent) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGCHLD, SIGPIPE}) std::signal(sig, SIG_DFL);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  const int null_in = ::open("/dev/null", O_RDONLY);
  const int null_out = ::open("/dev/null", O_WRONLY);
  ::dup2(null_in, STDIN_FILENO);
  ::dup2(null_out, STDOUT_FILENO);
  ::dup2(stderr_fd, STDERR_FILENO);
  int error = 0;
  if (::chdir(spec.working_dir.c_str()) != 0) {
    error = errno;
  } else {
    ::execvpe(argv[0], argv, envp);
    error = errno;
  }
  ssize_t written = ::write(status_fd, &error, sizeof error);
  (void)written;
  ::_exit(127);
}

/// Waits up to `timeout` for the child to end. A stop request meanwhile is remembered in `stop`
/// and, when `interruptible`, ends the wait.
bool wait_for(pid_t pid, int& status, Clock::duration timeout, const sigset_t& watched, int& stop,
              bool interruptible) {
  const Clock::time_point until = Clock::now() + timeout;
  while (true) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return true;
    const auto left = until - Clock::now();
    if (left <= Clock::duration::zero()) return false;
    const auto slice = std::min<Clock::duration>(left, std::chrono::milliseconds(50));
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(slice).count();
    timespec wait{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
    const int sig = ::sigtimedwait(&watched, nullptr, &wait);
    if ((sig == SIGINT || sig == SIGTERM || sig == SIGHUP) && stop == 0) {
      stop = sig;
      if (interruptible) return false;
    }
  }
}

/// SIGTERM to the group, SIGKILL after the grace period, and the leader reaped.
int end_group(pid_t pid, double grace_s, const sigset_t& watched, int& stop) {
  ::kill(-pid, SIGTERM);
  int status = 0;
  const auto grace =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace_s));
  if (!wait_for(pid, status, grace, watched, stop, /*interruptible=*/false)) {
    ::kill(-pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  return status;
}

}  // namespace

ProgramOutcome run_program(const ProgramSpec& spec) {
  ProgramOutcome outcome;
  std::vector<std::string> args = spec.argv;
  std::vector<std::string> env = environment_of(spec);
  const std::vector<char*> argv = pointers(args);
  const std::vector<char*> envp = pointers(env);
  const int stderr_fd =
      ::open(spec.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  int status_pipe[2];
  if (stderr_fd < 0 || ::pipe2(status_pipe, O_CLOEXEC) != 0) {
    outcome.process.start_error = "cannot open " + spec.stderr_path + ": " + std::strerror(errno);
    if (stderr_fd >= 0) ::close(stderr_fd);
    return outcome;
  }
  sigset_t watched, old_mask;
  sigemptyset(&watched);
  for (const int sig : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&watched, sig);
  ::pthread_sigmask(SIG_BLOCK, &watched, &old_mask);
  const Clock::time_point begin = Clock::now();
  const pid_t self = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) be_program(spec, argv.data(), envp.data(), stderr_fd, status_pipe[1], self);
  ::close(status_pipe[1]);
  ::close(stderr_fd);
  int stop = 0;
  if (pid < 0) {
    outcome.process.start_error = std::string("cannot fork: ") + std::strerror(errno);
  } else {
    ::setpgid(pid, pid);  // also here, so the group exists before any kill below
    int exec_error = 0;
    if (::read(status_pipe[0], &exec_error, sizeof exec_error) == sizeof exec_error) {
      outcome.process.start_error =
          "cannot start " + spec.argv[0] + ": " + std::strerror(exec_error);
    }
    int status = 0;
    const auto limit = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(spec.time_limit_s));
    if (!wait_for(pid, status, limit, watched, stop, /*interruptible=*/true)) {
      outcome.timed_out = stop == 0;
      status = end_group(pid, spec.grace_s, watched, stop);
    }
    ::kill(-pid, SIGKILL);  // whatever the program left running in its group
    if (outcome.process.start_error.empty()) outcome.process = process_result(status);
  }
  ::close(status_pipe[0]);
  outcome.wall_s = std::chrono::duration<double>(Clock::now() - begin).count();
  // A SIGCHLD still pending is dropped; a stop request goes back to this process.
  timespec none{0, 0};
  for (int sig; (sig = ::sigtimedwait(&watched, nullptr, &none)) > 0;) {
    if (stop == 0 && sig != SIGCHLD) stop = sig;
  }
  ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  if (stop != 0) ::raise(stop);
  return outcome;
}

}  // namespace msislab::app
