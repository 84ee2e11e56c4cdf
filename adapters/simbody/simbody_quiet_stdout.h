// Simbody's rigid-contact stepper (SemiExplicitEulerTimeStepper) in the Debian build prints four lines to
// stdout every step and more at each impact (engines.md), and `impactbench run` prints its results on
// stdout: file descriptor 1 goes to /dev/null while one of these lives and comes back when it ends.
#pragma once

namespace ib::simbody {

class QuietStdout {
 public:
  QuietStdout();
  ~QuietStdout();
  QuietStdout(const QuietStdout&) = delete;
  QuietStdout& operator=(const QuietStdout&) = delete;

 private:
  int saved_fd_ = -1;  // a duplicate of fd 1 as it was; -1 when nothing was redirected
};

}  // namespace ib::simbody
