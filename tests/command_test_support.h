// What the tests that drive the impactbench command share: running it and reading what it printed.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ib::test {

struct CommandOutput {
  int exit_code = -1;
  std::string text;  // stdout and stderr
};

// Runs `impactbench ARGUMENTS` (IMPACTBENCH_EXECUTABLE), its output captured in `log`.
inline CommandOutput run_impactbench(const std::string& arguments, const std::filesystem::path& log) {
  const std::string command = std::string(IMPACTBENCH_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  CommandOutput out;
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream buffer;
  buffer << in.rdbuf();
  out.text = buffer.str();
  return out;
}

}  // namespace ib::test
