// ODE as a process-wide library: initialised once (dInitODE2), checked to be the double-precision
// build, and with its message handlers installed so that what ODE reports reaches the run's reason
// and the job's log. The only global state of the adapter, as ODE's C API requires.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ib::ode {

// Initialises ODE for this process on first use (thread-safe; later calls only make sure the calling
// thread has ODE's per-thread data). Throws std::runtime_error when the library is not the
// double-precision build. ODE is closed (dCloseODE) when the process exits normally.
void ensure_initialised();

// "0.16.2 (double precision)": the headers' version and the library's own precision.
std::string version_text();

// A function defined in ODE's library (dGetConfiguration), whose address dladdr maps to the library's file.
const void* library_function();

// "dODE_VERSION 0.16.2": the version of the headers this adapter was compiled with.
std::string header_version_text();

// Collects the messages (warnings) ODE prints through dMessage while it is alive, on the thread that
// made it. ODE's handlers take no user pointer, so the collector is found through a thread-local
// pointer; collectors nest. ODE's errors and internal assertions (dError, dDebug) are written to
// stderr with their number and then ODE aborts the process, as it always does: the suite's job
// isolation turns that into a "failed" verdict that quotes the message (harness/suite/suite.h).
class MessageLog {
 public:
  MessageLog();
  ~MessageLog();
  MessageLog(const MessageLog&) = delete;
  MessageLog& operator=(const MessageLog&) = delete;

  static constexpr std::size_t kKept = 20;  // messages kept (and echoed to stderr) per log; the rest are counted

  const std::vector<std::string>& messages() const { return messages_; }  // the first kKept
  std::size_t count() const { return count_; }                            // all of them
  // Keeps the message if fewer than kKept are kept; returns whether it was kept.
  bool add(std::string message);

 private:
  std::vector<std::string> messages_;
  std::size_t count_ = 0;
  MessageLog* outer_;
};

}  // namespace ib::ode
