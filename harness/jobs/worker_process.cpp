// A job's process (worker_process.h).
#include "harness/jobs/worker_process.h"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace ib {

std::string describe_exit(int status, double time_limit_s, bool timed_out, const std::string& log_tail) {
  std::ostringstream why;
  if (timed_out)
    why << kTimeLimitReason << " of " << time_limit_s << " s";
  else if (WIFSIGNALED(status))
    why << "the job's process died of signal " << WTERMSIG(status) << " (" << strsignal(WTERMSIG(status)) << ")";
  else if (WIFEXITED(status))
    why << "the job's process exited with code " << WEXITSTATUS(status) << " without a result";
  else
    why << "the job's process ended abnormally";
  if (!log_tail.empty()) why << "; its last output: " << log_tail;
  return why.str();
}

bool stopped_from_outside(int status, bool timed_out) {
  if (timed_out || !WIFSIGNALED(status)) return false;
  const int signal = WTERMSIG(status);
  return signal == SIGTERM || signal == SIGINT || signal == SIGHUP || signal == SIGKILL || signal == SIGQUIT;
}

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last.size() > 300 ? last.substr(0, 300) + "..." : last;
}

// ---- Interruption: SIGINT and SIGTERM stop the suite between results, never in the middle of one.
// The handler only notes the signal; the runner stops its workers, records nothing half-done and
// returns. A terminal's Ctrl-C reaches the workers too (same process group): they die at once, and
// what they had not finished is not recorded, so that --resume runs it again.

volatile std::sig_atomic_t interrupt_signal = 0;

extern "C" void note_interruption(int signal) { interrupt_signal = signal; }

InterruptionHandler::InterruptionHandler() {
  interrupt_signal = 0;
  struct sigaction action {};
  action.sa_handler = note_interruption;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

InterruptionHandler::~InterruptionHandler() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

bool interrupted() { return interrupt_signal != 0; }

// Starts a job's process (fork) and returns its pid, as fork does. In the job's process: the default
// signal actions (the parent's handler would only set a flag nobody reads), and death with the parent, so
// that a suite killed with SIGKILL leaves no orphan writing into the folder a --resume is about to use.
// SIGINT and SIGTERM stay blocked from before the fork until the child has its default actions: one sent
// to the child in between would otherwise run the parent's handler, copied into the child, and be lost
// (the job then finished as if no one had stopped it); blocked, it waits and then ends the child.
pid_t fork_worker() {
  sigset_t stop_signals, previous;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigprocmask(SIG_BLOCK, &stop_signals, &previous);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  const int fork_error = errno;
  if (pid == 0) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);  // the parent died before prctl
  }
  sigprocmask(SIG_SETMASK, &previous, nullptr);
  errno = fork_error;
  return pid;
}

// ---- Write errors inside a job's process: the message goes to the parent through a pipe and the
// process exits with kWorkerOutputError; the parent stops the suite with that message (OutputError).
void send_and_exit(int pipe_fd, const std::string& message) {
  if (pipe_fd >= 0) {
    const ssize_t written = write(pipe_fd, message.data(), std::min<std::size_t>(message.size(), 4000));
    (void)written;
  }
  _exit(kWorkerOutputError);
}

std::string receive(int pipe_fd) {
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fd, buffer, sizeof buffer)) > 0;) message.append(buffer, static_cast<std::size_t>(n));
  return message;
}

}  // namespace ib
