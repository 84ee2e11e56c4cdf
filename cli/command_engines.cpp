// `engines [--json]`: every simulator of this build with its descriptor (model/simulator_descriptor.h):
// what it is, its library version, the Debian packages it comes from, its colours in the report and the
// diagnostics keys it writes into runs.jsonl, each with its meaning and unit. --json prints the text a
// suite writes to DIR/engines.json (harness/records/engines_file.h); --names the names alone, comma-separated.
#include "cli/commands.h"

#include <cstdio>
#include <memory>

#include "harness/records/engines_file.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

int command_engines(bool json, bool names) {
  const ib::SimulatorCatalog& catalog = ib::simulator_catalog();
  if (names) {  // for scripts: "reference,mujoco,..." as --engines takes it
    std::string list;
    for (const std::string& name : catalog.names) list += (list.empty() ? "" : ",") + name;
    std::printf("%s\n", list.c_str());
    return kExitOk;
  }
  if (json) {
    std::fputs(ib::engines_json(catalog).c_str(), stdout);
    return kExitOk;
  }
  for (const std::string& name : catalog.names) {
    const ib::SimulatorDescriptor d = ib::descriptor_of(catalog, name);
    const std::unique_ptr<ib::Simulator> simulator = catalog.make(name);
    std::printf("%s (%s): %s\n", d.name.c_str(), d.display_name.c_str(), d.summary.c_str());
    std::printf("  version: %s\n", simulator ? simulator->version().c_str() : "?");
    std::string packages;
    for (const std::string& p : d.packages) packages += (packages.empty() ? "" : ", ") + p;
    std::printf("  packages: %s\n", packages.empty() ? "none (built from this repository)" : packages.c_str());
    if (!d.colours.empty()) {
      std::printf("  colours:");
      for (const auto& [path, colour] : d.colours) std::printf(" %s %s", path.c_str(), colour.c_str());
      std::printf("\n");
    }
    std::printf("  diagnostics keys:\n");
    for (const ib::DiagnosticsKey& k : d.diagnostics)
      std::printf("    %-36s %s%s%s\n", k.key.c_str(), k.meaning.c_str(), k.unit.empty() ? "" : " [",
                  k.unit.empty() ? "" : (k.unit + "]").c_str());
  }
  return kExitOk;
}

}  // namespace

Command add_engines_command(CLI::App& app) {
  auto flags = std::make_shared<std::pair<bool, bool>>(false, false);  // --json, --names
  CLI::App* engines = app.add_subcommand(
      "engines", "every simulator of this build: name, version, Debian packages, report colours, diagnostics keys");
  engines->add_flag("--json", flags->first, "print the descriptors as JSON (what a suite writes to DIR/engines.json)");
  engines->add_flag("--names", flags->second, "print the simulators' names alone, comma-separated (for --engines)")
      ->excludes("--json");
  return {engines, [flags] { return command_engines(flags->first, flags->second); }};
}

}  // namespace cli
