#include "harness/records/folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <fstream>
#include <sstream>

#include "harness/records/run_files.h"

namespace ib {

FolderLock::FolderLock(const std::string& folder, const std::string& command) {
  const std::string path = folder + "/.impactbench.lock";
  // O_CLOEXEC: a program the command starts does not hold the folder; its own forked workers do (they
  // share this descriptor), so the folder stays held until the last of them has gone.
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw OutputError(output_error_text(path, "create the folder's lock file", errno));
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    close(fd_);
    fd_ = -1;
    if (error != EWOULDBLOCK) throw OutputError(output_error_text(path, "lock the folder", error));
    std::ifstream in(path);
    std::string holder;
    std::getline(in, holder);
    throw FolderBusy(folder + ": another impactbench command is writing into this folder (" +
                     (holder.empty() ? std::string("its lock file names no process") : holder) +
                     "); wait for it to end, stop it, or choose another --out");
  }
  // Who holds it, for the message above (the lock itself is the flock, not this text).
  char started[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  std::ostringstream text;
  text << command << ", process " << getpid() << ", started " << started << "\n";
  const std::string line = text.str();
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, line.data(), line.size(), 0) != static_cast<ssize_t>(line.size())) {
    const int error = errno;
    close(fd_);
    fd_ = -1;
    throw OutputError(output_error_text(path, "write the folder's lock file", error));
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) close(fd_);  // the file stays: removing it could race with the next holder's open
}

}  // namespace ib
