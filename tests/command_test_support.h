// What the tests that drive the impactbench command share: running it and reading what it printed.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
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

// A shell command (e.g. zcat, as a user reads a gzipped series) and what it printed on stdout.
inline CommandOutput run_command(const std::string& command) {
  CommandOutput out;
  if (std::FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.text.append(buffer, n);
    const int status = ::pclose(pipe);
    out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return out;
}

// `impactbench ARGUMENTS` with its output in a log file of this process named after prefix (removed after).
inline CommandOutput run_impactbench_logged_as(const std::string& arguments, const std::string& log_prefix) {
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() / (log_prefix + std::to_string(::getpid()) + ".log");
  CommandOutput out = run_impactbench(arguments, log);
  std::filesystem::remove(log);
  return out;
}

// A file of this process in the temporary directory, PREFIX + pid + "-" + NAME + ".toml", holding `text` (a study
// file a test writes).
inline std::filesystem::path temporary_toml_file(const std::string& prefix, const std::string& name,
                                                 const std::string& text) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + "-" + name + ".toml");
  std::ofstream(path) << text;
  return path;
}

// A published scenario's file: scenarios/paper/NAME.toml.
inline std::string paper_scenario(const std::string& name) {
  return std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/" + name + ".toml";
}

// A folder of this process in the temporary directory, PREFIX + NAME, removed if it was there (not created).
inline std::filesystem::path fresh_command_folder(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

}  // namespace ib::test
