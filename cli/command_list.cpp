// `list`: the scenarios of a folder, the simulators of this build, their laws and options.
#include "cli/commands.h"

#include <cstdio>
#include <exception>
#include <memory>

#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

int command_list(const std::string& folder) {
  std::printf("scenarios in %s:\n", folder.c_str());
  for (const std::string& file : ib::find_scenario_files(folder)) {
    try {
      const ib::Scenario s = ib::load_scenario(file);
      std::printf("  %-24s %s\n", s.name.c_str(), file.c_str());
    } catch (const std::exception& e) {
      std::printf("  (unreadable)             %s\n", e.what());
    }
  }
  std::printf("engines:");
  for (const auto& n : ib::simulator_names()) std::printf(" %s", n.c_str());
  std::printf("\nlaws: hertz viscoelastic newton\n");
  for (const auto& n : ib::simulator_names()) {
    std::printf("options of %s:\n", n.c_str());
    for (const auto& [key, help] : ib::make_simulator(n)->option_help())
      std::printf("  %-18s %s\n", key.c_str(), help.c_str());
  }
  return kExitOk;
}

}  // namespace

Command add_list_command(CLI::App& app) {
  auto folder = std::make_shared<std::string>(IMPACTBENCH_SCENARIO_DIR);
  CLI::App* list = app.add_subcommand("list", "the scenarios, engines, laws and simulator options of this build");
  list->add_option("folder", *folder, "scenario folder")->capture_default_str();
  return {list, [folder] { return command_list(*folder); }};
}

}  // namespace cli
