#include "cli/commands.h"

#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/records/number_text.h"

extern char** environ;

namespace cli {

// Two folders are compared by reports/compare.py (Python: it reads the results as the report does, with its
// ensembles' intervals), run with its arguments as given (no shell between), its exit code passed through.
int command_compare(const CompareOptions& o) {
  std::vector<std::string> arguments = {IMPACTBENCH_PYTHON,
                                        std::string(IMPACTBENCH_SOURCE_DIR) + "/reports/compare.py"};
  arguments.insert(arguments.end(), o.folders.begin(), o.folders.end());
  arguments.insert(arguments.end(), {"--cost-noise", ib::number_text(o.cost_noise)});
  for (const auto& [flag, value] : {std::pair{"--json", o.json}, {"--markdown", o.markdown}, {"--html", o.html}})
    if (!value.empty()) arguments.insert(arguments.end(), {flag, value});
  if (o.cost_across_machines) arguments.push_back("--cost-across-machines");
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  pid_t child = 0;
  if (posix_spawn(&child, argv[0], nullptr, nullptr, argv.data(), environ) != 0)
    throw std::runtime_error(std::string("could not start ") + argv[0] + " for the comparison");
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
  }
  // 0 nothing moved, 1 moved, 2 bad input, 3 a file it could not write (said by it); anything else is its failure
  if (!WIFEXITED(status) || WEXITSTATUS(status) > kExitOutputError)
    throw std::runtime_error("the comparison could not be made (reports/compare.py failed)");
  return WEXITSTATUS(status);
}

}  // namespace cli
