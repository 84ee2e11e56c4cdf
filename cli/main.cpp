// impactbench: the command line. Exit codes:
//   0    every run ok (or inaccurate)
//   1    some run unstable or failed (its files and reason are still written)
//   2    bad usage or input (the message names the file, line, key or option, the value and what is allowed)
//   3    a result could not be written (full disk, unwritable folder): the message names the file, the
//        OS's reason and what to do; everything recorded before it is kept, and `suite --resume` goes on
//   4    `merge` joined what exists, but a shard lacks results (a failed array task): the message names the
//        shard, what it lacks and the command that finishes it
//   130  `suite` stopped by SIGINT (143: SIGTERM), every finished result kept; the message says how to resume
#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include "cli/commands.h"
#include "harness/records/provenance_file.h"
#include "harness/records/run_files.h"
#include "simulators/catalog.h"

int main(int argc, char** argv) {
  using namespace cli;
  g_argc = argc;
  g_argv = argv;
  CLI::App app{"impactbench: a benchmark of physics engines on a two-frame vibro-impact rig"};
  app.require_subcommand(1);
  // each command's options beside it (cli/command_<name>.cpp); this order is the help's
  const std::vector<Command> commands = {add_modes_command(app),   add_run_command(app),    add_suite_command(app),
                                         add_merge_command(app),   add_export_command(app), add_score_command(app),
                                         add_report_command(app),  add_repro_command(app),  add_compare_command(app),
                                         add_sweep_command(app),   add_study_command(app),  add_engines_command(app),
                                         add_metrics_command(app), add_list_command(app)};
  app.set_version_flag(
      "--version", [] { return ib::version_text(ib::simulator_catalog()); },
      "impactbench's commit and build, and each engine's library version");
  if (const std::optional<std::string> unknown = unknown_command(app, argc, argv)) {
    std::fprintf(stderr, "impactbench: %s\n", unknown->c_str());
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const std::invalid_argument& error) {  // a shared option's value, checked as it is read (option_rules.h)
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
  try {
    for (const Command& command : commands)
      if (command.app->parsed()) return command.run();
    return kExitBadInput;  // unreachable: CLI11 requires one subcommand
  } catch (const ib::OutputError& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitOutputError;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
}
