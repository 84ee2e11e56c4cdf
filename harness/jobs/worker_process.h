// A job's process, the same for the suite and the sweep: starting it (fork_worker), telling why it ended
// (describe_exit, stopped_from_outside), passing a write error back (send_and_exit, receive), and the
// runner's own interruption (SIGINT, SIGTERM: InterruptionHandler).
#pragma once

#include <sys/types.h>

#include <csignal>
#include <string>

namespace ib {

// The reason of a job stopped at its time limit begins with this (its record's timed_out is set).
constexpr const char* kTimeLimitReason = "stopped after the time limit";

// Why a job's process ended without a record, for its failed row; its log's last line, cut at 300 characters.
std::string describe_exit(int status, double time_limit_s, bool timed_out, const std::string& log_tail);
std::string last_line(const std::string& path);

// A job's process ended by a signal from outside (a scheduler stopping the task, a person, the OOM killer:
// SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGKILL), not by its time limit: its run decided nothing about the
// simulator, so it is not recorded and --resume runs it again. Slurm and systemd send SIGTERM to every
// process of a task in no particular order: a worker can get it before the suite does. A crash (SIGSEGV,
// SIGABRT, SIGFPE, ...) is a finding.
bool stopped_from_outside(int status, bool timed_out);

// ---- Interruption: SIGINT and SIGTERM stop the suite between results, never in the middle of one.
// The handler only notes the signal; the runner stops its workers, records nothing half-done and
// returns. A terminal's Ctrl-C reaches the workers too (same process group): they die at once, and
// what they had not finished is not recorded, so that --resume runs it again.
extern volatile std::sig_atomic_t interrupt_signal;

// Installs the handler for the runner's lifetime and restores the previous one after.
class InterruptionHandler {
 public:
  InterruptionHandler();
  ~InterruptionHandler();
  InterruptionHandler(const InterruptionHandler&) = delete;
  InterruptionHandler& operator=(const InterruptionHandler&) = delete;

 private:
  struct sigaction previous_int_ {
  }, previous_term_{};
};

bool interrupted();

// Starts a job's process (fork's return value): in it, the default signal actions and death with the
// parent; a SIGINT or SIGTERM sent to it at any moment, even during the fork, ends it (worker_process.cpp).
pid_t fork_worker();

// ---- Write errors inside a job's process: the message goes to the parent through a pipe and the
// process exits with this code; the parent stops the suite with that message (OutputError).
constexpr int kWorkerOutputError = 75;
[[noreturn]] void send_and_exit(int pipe_fd, const std::string& message);
std::string receive(int pipe_fd);

}  // namespace ib
