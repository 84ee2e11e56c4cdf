// The processes a test starts and signals, seen as a shell and a scheduler see them: started in a process
// group of their own, waited for, stopped, and found by parent or group in /proc (suite_interruption_test.cpp).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace process_control {

namespace fs = std::filesystem;

// Starts the command in a process group of its own (as a shell does), output to `log`.
inline pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  setpgid(pid, pid);  // also here: no race with the signal below
  return pid;
}

inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::size_t lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.empty() ? 0 : 1;
  return n;
}

// One process's state, parent and process group, from /proc/PID/stat (state 0 when it is gone).
struct ProcessStat {
  char state = 0;
  long parent = 0;
  long group = 0;
};
inline ProcessStat process_stat(const fs::path& proc_entry) {
  const std::string stat = read_text(proc_entry / "stat");
  const auto close = stat.rfind(')');
  ProcessStat s;
  if (close == std::string::npos) return s;
  std::istringstream rest(stat.substr(close + 2));
  rest >> s.state >> s.parent >> s.group;
  return s;
}
inline bool alive(const ProcessStat& s) { return s.state != 0 && s.state != 'Z' && s.state != 'X'; }

// The live (not zombie) processes for which `keep` holds, from /proc.
template <class Keep>
inline std::vector<pid_t> live_processes(Keep keep) {
  std::vector<pid_t> found;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const ProcessStat s = process_stat(entry.path());
    if (alive(s) && keep(s)) found.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return found;
}
inline int live_processes_in_group(pid_t group) {
  return static_cast<int>(live_processes([group](const ProcessStat& s) { return s.group == group; }).size());
}
inline std::vector<pid_t> children_of(pid_t parent) {
  return live_processes([parent](const ProcessStat& s) { return s.parent == parent; });
}

// Stops (SIGSTOP) one live child of `parent` and returns it, or -1 if none is left before `deadline`. A
// stopped worker cannot finish its job, so the signal sent to it next is the one that ends it. Found early,
// the worker is often just forked: before fork_worker blocked SIGTERM across the fork, a signal there ran
// the suite's copied handler and was lost (the suite then finished every job and exited 1).
inline pid_t freeze_one_child(pid_t parent, std::chrono::steady_clock::time_point deadline) {
  while (std::chrono::steady_clock::now() < deadline) {
    for (pid_t child : children_of(parent)) {
      kill(child, SIGSTOP);
      for (int i = 0; i < 400; ++i) {  // until the stop shows (at most 2 s) or the child is gone
        const ProcessStat s = process_stat("/proc/" + std::to_string(child));
        if (s.state == 'T' || s.state == 't') return child;
        if (!alive(s)) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return -1;
}

}  // namespace process_control
