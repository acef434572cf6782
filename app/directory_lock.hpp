// One writer per output directory: an exclusive lock on DIR/.lock (flock), held while a command
// writes there and released by the kernel when the process ends, however it ends.
#pragma once

#include <string>

namespace msislab::app {

class DirectoryLock {
 public:
  /// Creates dir if needed and locks it for `command` (written into the lock file, with this
  /// process's id, for whoever finds it held). Throws io::InputError naming the directory and the
  /// holder when another process holds it.
  DirectoryLock(const std::string& dir, const std::string& command);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

  /// The lock's file descriptor (a forked worker closes it, so the lock ends with its holder).
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace msislab::app
