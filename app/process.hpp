// Child processes for the Monte Carlo runs: the msislab executable started with posix_spawn, its
// stdout discarded and its stderr kept in a file, and how it ended.
#pragma once

#include <string>
#include <vector>

namespace msislab::app {

struct ProcessResult {
  bool exited = false;  ///< false: killed by a signal (or could not be started)
  int exit_code = -1;
  int signal = 0;
  std::string start_error;  ///< why it could not be started; empty when it ran
  bool ok() const { return exited && exit_code == 0; }
};

/// Runs argv[0] with the arguments, stdin and stdout on /dev/null and stderr into stderr_path,
/// and waits for it. Safe to call from several threads at once.
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& stderr_path);

/// How a child ended, from its waitpid status.
ProcessResult process_result(int wait_status);

/// "exit status 2", "killed by signal 9 (Killed)" or the start error, then ": " and the last
/// non-empty line of the stderr file when there is one.
std::string describe_failure(const ProcessResult& result, const std::string& stderr_path);

/// The absolute path of the running executable (/proc/self/exe).
std::string self_executable();

}  // namespace msislab::app
