#include "adapters/simbody/simbody_quiet_stdout.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace ib::simbody {

QuietStdout::QuietStdout() {
  // what was written before belongs on the real stdout
  std::cout.flush();
  std::fflush(stdout);
  const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null_fd < 0) return;  // nothing silenced: the output is only noisier
  saved_fd_ = dup(STDOUT_FILENO);
  if (saved_fd_ < 0 || dup2(null_fd, STDOUT_FILENO) < 0) {
    if (saved_fd_ >= 0) close(saved_fd_);
    saved_fd_ = -1;
  }
  close(null_fd);
}

QuietStdout::~QuietStdout() {
  if (saved_fd_ < 0) return;
  // Simbody's lines still buffered go to /dev/null, not to the restored stdout
  std::cout.flush();
  std::fflush(stdout);
  dup2(saved_fd_, STDOUT_FILENO);
  close(saved_fd_);
}

}  // namespace ib::simbody
