// The engines a test of the harness or the command runs, read from the build's catalog: such a test needs
// engines, never particular ones (an engine's own behaviour is tested in tests/<engine>_*_test.cpp), so it
// names none and runs with whatever engines the build has (docs/adding-an-engine.md). In the catalog's
// order (adapters/CMakeLists.txt), so that a test runs the same engines from one run to the next.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace ib::test {

// The engines among simulators' names (simulator_names(), or `engines --names` split): the reference left out.
inline std::vector<std::string> engines_among(const std::vector<std::string>& simulators) {
  std::vector<std::string> engines;
  for (const std::string& name : simulators)
    if (!name.empty() && name != "reference") engines.push_back(name);
  return engines;
}

// "reference,e1,e2\n" (what `impactbench engines --names` prints) as its names.
inline std::vector<std::string> split_names(const std::string& comma_separated) {
  std::vector<std::string> names;
  std::stringstream in(comma_separated);
  for (std::string name; std::getline(in, name, ',');) {
    while (!name.empty() && (name.back() == '\n' || name.back() == ' ')) name.pop_back();
    names.push_back(name);
  }
  return names;
}

// The first n engines of `engines` (fewer when the build has fewer), joined with "," after `first`
// ("reference,e1,e2"): an --engines value.
inline std::string engines_option(const std::string& first, const std::vector<std::string>& engines, std::size_t n) {
  std::string list = first;
  for (std::size_t i = 0; i < engines.size() && i < n; ++i) list += (list.empty() ? "" : ",") + engines[i];
  return list;
}

#ifdef IMPACTBENCH_EXECUTABLE
// The engines of the impactbench command under test (`engines --names`), for tests that only drive the
// command; empty when it cannot say.
inline std::vector<std::string> command_engines() {
  std::string text;
  if (std::FILE* pipe = ::popen((std::string(IMPACTBENCH_EXECUTABLE) + " engines --names").c_str(), "r")) {
    char buffer[1024];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
    const int status = ::pclose(pipe);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return {};
  }
  return engines_among(split_names(text));
}
#endif

}  // namespace ib::test
