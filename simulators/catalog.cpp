// The simulators built into this binary (catalog.h): the reference, then the engines in the order of
// IMPACTBENCH_ENGINES (adapters/CMakeLists.txt: registering an engine is adding its name there,
// docs/adding-an-engine.md).
#include "simulators/catalog.h"

#include "reference/reference_simulator.h"

// the engines of this build (generated from IMPACTBENCH_ENGINES by simulators/CMakeLists.txt)
#define IMPACTBENCH_ENGINE_INCLUDES
#include "engines.inc"
#undef IMPACTBENCH_ENGINE_INCLUDES

namespace ib {

namespace {
struct Entry {
  const char* name;
  std::unique_ptr<Simulator> (*make)();
};
const Entry kSimulators[] = {
    {"reference", make_reference_simulator},
#include "engines.inc"
};
// Each simulator's descriptor.json as read at configure time (simulators/descriptor.cmake), the
// reference first, in the order of kSimulators. A function's static, not a namespace-scope array: its
// strings are made at run time, and a test's cases (built during static initialisation from
// simulator_names()) may ask for the catalog before this file's statics exist.
const std::vector<SimulatorDescriptor>& descriptors() {
#define IMPACTBENCH_ENGINE_DESCRIPTORS
  static const std::vector<SimulatorDescriptor> all = {
#include "engines.inc"
  };
#undef IMPACTBENCH_ENGINE_DESCRIPTORS
  return all;
}
}  // namespace

const SimulatorCatalog& simulator_catalog() {
  static const SimulatorCatalog catalog = [] {
    SimulatorCatalog c;
    for (const Entry& e : kSimulators) c.names.push_back(e.name);
    c.make = [](const std::string& name) -> std::unique_ptr<Simulator> {
      for (const Entry& e : kSimulators)
        if (name == e.name) return e.make();
      return nullptr;
    };
    c.chain_reference_options = chain_reference_options;
    c.descriptors = descriptors();
    return c;
  }();
  return catalog;
}

std::vector<std::string> simulator_names() { return simulator_catalog().names; }

std::unique_ptr<Simulator> make_simulator(const std::string& name) { return simulator_catalog().make(name); }

}  // namespace ib
