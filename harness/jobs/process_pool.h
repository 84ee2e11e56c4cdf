// The one pool of worker processes: a suite's jobs, a step search's probes, a sweep's chains, a study's every
// unit and `run --time-limit` all run through it. Each unit in its own process (worker_process.h), so that a
// crash, an abort or a hang inside an engine's library costs that unit alone; its time limit; the message pipe
// for a write error; and how it ended, handed back to whoever started it, which records it. Which unit runs
// next is not the pool's business (unit_source.h).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ib {

// How a unit's process ended.
struct ProcessEnd {
  std::string unit;          // the id it was started with
  int status = 0;            // as waitpid gives it
  bool timed_out = false;    // the pool stopped it at its time limit
  std::string output_error;  // the write error it sent before exiting with kWorkerOutputError ("": none)
  double wall_time_s = 0;    // from its start to its end
};

struct ProcessStart {
  std::string unit;         // unique among the running units
  double time_limit_s = 0;  // > 0: killed when it has run this long since its start or its last restart_clock
  std::string log_path;     // its stdout and stderr; "": the parent's
  bool append_log = false;  // a chain's log grows with each process that continues it
};

// What runs in the unit's process: it never returns (it _exits); a write error goes through message_pipe
// (send_and_exit, worker_process.h).
using ProcessBody = std::function<void(int message_pipe)>;

class ProcessPool {
 public:
  ProcessPool() = default;
  ~ProcessPool() { kill_all(); }  // none of its processes outlives the pool
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  std::size_t running() const { return running_.size(); }
  // Throws std::runtime_error when the process or its pipe cannot be made.
  void start(const ProcessStart& how, const ProcessBody& body);
  // The unit's time limit counts again from now (a sweep's limit is per ratio: its chain restarts it).
  void restart_clock(const std::string& unit);
  // One process that has ended, without waiting; the time limits are enforced first. None: none ended.
  std::optional<ProcessEnd> next_end();
  // Waits for a process to end; none when none runs or the runner was interrupted (worker_process.h).
  std::optional<ProcessEnd> wait_end();
  // Stops the pool: the processes that had ended already are returned (nothing finished is lost); the others
  // are killed and not returned (a resume runs them again).
  std::vector<ProcessEnd> stop();

 private:
  using Clock = std::chrono::steady_clock;
  struct Running {
    std::string unit;
    Clock::time_point started, clock;  // clock: what the time limit counts from
    double time_limit_s = 0;
    bool timed_out = false;
    int message_pipe = -1;  // read end
  };
  ProcessEnd ended(pid_t pid, int status);
  void kill_all();
  std::map<pid_t, Running> running_;
};

}  // namespace ib
