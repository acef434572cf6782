// One writer per output directory: an exclusive lock on DIR/.lock (flock), held while a command
// writes there and released by the kernel when the process ends, however it ends.
#pragma once

#include <string>

#include "io/output_guard.hpp"

namespace msislab::app {

class DirectoryLock {
 public:
  /// Claims the output folder (io::claim_output_folder: created with its marker, or an earlier
  /// output of the same kind) and locks it for `holder` (written into the lock file, with this
  /// process's id, for whoever finds it held). Throws io::InputError naming the directory: a
  /// folder msislab may not write, or one another process holds.
  DirectoryLock(const io::OutputRequest& output, const std::string& holder);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

  /// The lock's file descriptor (a forked worker closes it, so the lock ends with its holder).
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace msislab::app
