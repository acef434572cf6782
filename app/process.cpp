#include "app/process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>

#include "io/text_lines.hpp"

extern char** environ;

namespace msislab::app {

ProcessResult run_process(const std::vector<std::string>& argv, const std::string& stderr_path) {
  ProcessResult result;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    result.start_error = "cannot start " + argv[0] + ": " + std::strerror(error);
    return result;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      result.start_error = std::string("waitpid failed: ") + std::strerror(errno);
      return result;
    }
  }
  return process_result(status);
}

ProcessResult process_result(int wait_status) {
  ProcessResult result;
  if (WIFEXITED(wait_status)) {
    result.exited = true;
    result.exit_code = WEXITSTATUS(wait_status);
  } else if (WIFSIGNALED(wait_status)) {
    result.signal = WTERMSIG(wait_status);
  }
  return result;
}

std::string describe_failure(const ProcessResult& result, const std::string& stderr_path) {
  std::string text;
  if (!result.start_error.empty()) {
    text = result.start_error;
  } else if (result.exited) {
    text = "exit status " + std::to_string(result.exit_code);
  } else {
    text =
        "killed by signal " + std::to_string(result.signal) + " (" + strsignal(result.signal) + ")";
  }
  const std::string line = io::last_line(stderr_path);
  return line.empty() ? text : text + ": " + line;
}

std::string self_executable() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

}  // namespace msislab::app
