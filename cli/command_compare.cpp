#include "cli/commands.h"

#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/records/number_text.h"

extern char** environ;

namespace cli {

namespace {

// `compare BASE NEW [MORE ...]`: result folders side by side, made by reports/compare.py (docs/compare.md):
// what differs between what made them, then what moved beyond the noise; with more than two, each folder
// against the next (a history). Its exit code: 0 nothing moved, 1 something moved and nothing regressed, 2 bad
// input, 3 a file it could not write, 4 something regressed (docs/compare.md: a CI job gates on 4).
struct CompareOptions {
  std::vector<std::string> folders;  // the baseline first, each next one judged against the one before
  std::string json, markdown, html;  // files to write (html: a folder), none when empty
  bool cost_across_machines = false;
  double cost_noise = 0.3;  // the least relative change of CPU time told apart from a shared machine's drift
};

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
  // its exit codes (above), passed through; anything else is its failure
  constexpr int kExitRegressed = 4;
  if (!WIFEXITED(status) || WEXITSTATUS(status) > kExitRegressed)
    throw std::runtime_error("the comparison could not be made (reports/compare.py failed)");
  return WEXITSTATUS(status);
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* compare = app.add_subcommand("compare",
                                         "put two result folders side by side: what differs between what made "
                                         "them, then what moved beyond the noise (exit 1 when something did, 4 when "
                                         "something regressed)");
  compare
      ->add_option("folders", o->folders,
                   "BASE NEW: the baseline result folder (a suite's or a study's) and the one judged against it; "
                   "or several in order, each judged against the one before")
      ->required()
      ->expected(2, -1);
  compare->add_option("--json", o->json, "write the comparison as JSON to this file");
  compare->add_option("--markdown", o->markdown, "write the comparison as Markdown to this file");
  compare->add_option("--html", o->html,
                      "write compare.html (a figure per moved configuration) and compare.md into this folder");
  compare->add_flag("--cost-across-machines", o->cost_across_machines,
                    "judge CPU costs timed on other machines too (not comparable by default)");
  compare
      ->add_option("--cost-noise", o->cost_noise,
                   "the least relative change of CPU time told apart from the machine's drift between identical runs")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  return {compare, [o] { return command_compare(*o); }};
}

}  // namespace cli
