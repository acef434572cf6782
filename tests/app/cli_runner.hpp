// Runs the msislab executable from a test (its path is MSISLAB_EXE, set by
// tests/app/CMakeLists.txt) and captures its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "test_support.hpp"

namespace msislab::testing {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Single-quotes text for the shell.
inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char ch : text) quoted += (ch == '\'') ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

/// Runs a shell command (its words already quoted) with stdout and stderr captured in files of
/// tmp and no stdin.
inline CliResult run_shell(const std::string& command, const TempDir& tmp) {
  const std::string out = tmp.file("stdout.txt");
  const std::string err = tmp.file("stderr.txt");
  const int status = std::system(
      (command + " >" + shell_quote(out) + " 2>" + shell_quote(err) + " </dev/null").c_str());
  CliResult result;
  if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

#ifdef MSISLAB_EXE
/// Runs `msislab ARGS` (ARGS already quoted), as run_shell. `launcher` goes before the
/// executable, e.g. "env -u DISPLAY".
inline CliResult run_msislab(const std::string& args, const TempDir& tmp,
                             const std::string& launcher = "") {
  return run_shell(launcher + " " + shell_quote(MSISLAB_EXE) + " " + args, tmp);
}
#endif

}  // namespace msislab::testing
