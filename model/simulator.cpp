#include "model/simulator.h"

#include <memory>

namespace ib {

double series_start_s(const RunSettings& settings, const Scenario& scenario) {
  return settings.series_start_s >= 0 ? settings.series_start_s : scoring_window(scenario).start_s;
}

SimulatorDescriptor descriptor_of(const SimulatorCatalog& catalog, const std::string& name) {
  for (const SimulatorDescriptor& d : catalog.descriptors)
    if (d.name == name) return d;
  // a test's catalog, or a simulator without a descriptor file: known by its name alone
  SimulatorDescriptor bare;
  bare.name = name;
  bare.display_name = name;
  return bare;
}

std::string version_of(const SimulatorCatalog& catalog, const std::string& name) {
  const std::unique_ptr<Simulator> simulator = catalog.make ? catalog.make(name) : nullptr;
  return simulator ? simulator->version() : "";
}

LibraryBuild library_build_of(const SimulatorCatalog& catalog, const std::string& name) {
  const std::unique_ptr<Simulator> simulator = catalog.make ? catalog.make(name) : nullptr;
  return simulator ? simulator->library_build() : LibraryBuild{};
}

}  // namespace ib
