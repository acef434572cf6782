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

/// python3 as CMake found it when the build was configured ("" when it was not found).
inline std::string python3() {
#ifdef MSISLAB_PYTHON3
  return MSISLAB_PYTHON3;
#else
  return "";
#endif
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

/// A test that runs one of tools/*.py: it fails, never skips, when the build was configured
/// without python3, so a machine without it cannot pass the suite by leaving these tests out.
#define MSISLAB_REQUIRE_PYTHON3()                                                            \
  do {                                                                                       \
    if (::msislab::testing::python3().empty())                                               \
      GTEST_FAIL() << "python3 was not found when this build was configured, and this test " \
                      "runs a tools/*.py script: install python3 and python3-yaml "          \
                      "(tools/install_deps.sh test) and configure again";                    \
  } while (0)
