// A program of the user's (an external method, docs/formats.md) run without a shell: its own
// process group, a working folder, a time limit, stdin and stdout on /dev/null, stderr into a
// file. It never outlives the call: at the time limit, and when this process is asked to stop
// (SIGINT, SIGTERM, SIGHUP), its whole group gets SIGTERM and, after a grace period, SIGKILL.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/process.hpp"

namespace msislab::app {

struct ProgramSpec {
  std::vector<std::string> argv;  ///< argv[0] is looked up in PATH when it has no '/'
  /// Set in the program's environment on top of this process's.
  std::vector<std::pair<std::string, std::string>> environment;
  std::string working_dir;
  std::string stderr_path;
  double time_limit_s = 0.0;  ///< > 0
  double grace_s = 2.0;       ///< between SIGTERM and SIGKILL
};

struct ProgramOutcome {
  ProcessResult process;  ///< how it ended (start_error when it could not be started)
  bool timed_out = false;
  double wall_s = 0.0;
};

/// Runs the program and waits for it and its process group. A stop request that arrives
/// meanwhile ends the group and is then raised again in this process (which it then ends, unless
/// handled). Must be the only thread of the process that forks or waits for children.
ProgramOutcome run_program(const ProgramSpec& spec);

}  // namespace msislab::app
