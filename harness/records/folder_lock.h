// One owner per output folder: a suite, a sweep or a merge holds DIR/.impactbench.lock (flock) while it
// writes, so that a second command on the same folder (a relaunch, a requeued Slurm task, a person) is
// refused instead of running every job twice into it. The kernel drops the lock when its holder dies, kill
// -9 included: a dead process never holds a folder.
#pragma once

#include <stdexcept>
#include <string>

namespace ib {

// Another process holds the folder: bad input for this command (exit 2), whose message says who holds it.
class FolderBusy : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class FolderLock {
 public:
  // Locks `folder` (which must exist) for `command` (e.g. "suite"); throws FolderBusy naming the folder
  // and the holder's command, process id and start time when another process holds it, OutputError
  // (run_files.h) when the lock file cannot be made.
  FolderLock(const std::string& folder, const std::string& command);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace ib
