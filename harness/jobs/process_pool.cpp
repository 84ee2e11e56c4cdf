#include "harness/jobs/process_pool.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "harness/jobs/worker_process.h"

namespace ib {

void ProcessPool::start(const ProcessStart& how, const ProcessBody& body) {
  std::fflush(nullptr);  // what the parent printed is not printed again by the child
  int message_pipe[2] = {-1, -1};
  if (pipe2(message_pipe, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot start a worker process: pipe: ") + std::strerror(errno));
  const pid_t pid = fork_worker();
  if (pid < 0) {
    const int error = errno;
    close(message_pipe[0]);
    close(message_pipe[1]);
    throw std::runtime_error(std::string("cannot start a worker process: ") + std::strerror(error));
  }
  if (pid == 0) {
    close(message_pipe[0]);
    if (!how.log_path.empty()) {
      const int log = open(how.log_path.c_str(), O_WRONLY | O_CREAT | (how.append_log ? O_APPEND : O_TRUNC), 0644);
      if (log >= 0) {
        dup2(log, STDOUT_FILENO);
        dup2(log, STDERR_FILENO);
        close(log);
      }
    }
    body(message_pipe[1]);
    std::fflush(nullptr);
    _exit(0);  // a body that returns ends its process as a clean one would
  }
  close(message_pipe[1]);
  const Clock::time_point now = Clock::now();
  running_.emplace(pid, Running{how.unit, now, now, how.time_limit_s, false, message_pipe[0]});
}

void ProcessPool::restart_clock(const std::string& unit) {
  for (auto& [pid, r] : running_)
    if (r.unit == unit) r.clock = Clock::now();
}

ProcessEnd ProcessPool::ended(pid_t pid, int status) {
  const Running r = running_.at(pid);
  running_.erase(pid);
  ProcessEnd end;
  end.unit = r.unit;
  end.status = status;
  end.timed_out = r.timed_out;
  end.output_error = receive(r.message_pipe);  // the write end closed with the process: this does not block
  close(r.message_pipe);
  end.wall_time_s = std::chrono::duration<double>(Clock::now() - r.started).count();
  return end;
}

std::optional<ProcessEnd> ProcessPool::next_end() {
  const Clock::time_point now = Clock::now();
  for (auto& [pid, r] : running_) {
    if (!r.timed_out && r.time_limit_s > 0 && std::chrono::duration<double>(now - r.clock).count() > r.time_limit_s) {
      r.timed_out = true;
      kill(pid, SIGKILL);
    }
  }
  for (int status = 0;;) {
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) return std::nullopt;
    if (running_.count(pid)) return ended(pid, status);
    // not one of the pool's: a child some other code started and waits for itself
  }
}

std::optional<ProcessEnd> ProcessPool::wait_end() {
  while (!running_.empty() && !interrupted()) {
    if (auto end = next_end()) return end;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

std::vector<ProcessEnd> ProcessPool::stop() {
  std::vector<ProcessEnd> finished;
  for (int status = 0;;) {
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) break;
    if (running_.count(pid)) finished.push_back(ended(pid, status));
  }
  kill_all();
  return finished;
}

void ProcessPool::kill_all() {
  for (const auto& [pid, r] : running_) kill(pid, SIGKILL);
  for (const auto& [pid, r] : running_) {
    waitpid(pid, nullptr, 0);
    close(r.message_pipe);
  }
  running_.clear();
}

}  // namespace ib
