// The simulators built into this binary (catalog.h). Registering an engine is one line in kSimulators
// (docs/adding-an-engine.md).
#include "simulators/catalog.h"

#include "reference/reference_simulator.h"

#if IMPACTBENCH_WITH_MUJOCO
#include "adapters/mujoco/mujoco_simulator.h"
#endif
#if IMPACTBENCH_WITH_ODE
#include "adapters/ode/ode_simulator.h"
#endif
#if IMPACTBENCH_WITH_BULLET
#include "adapters/bullet/bullet_simulator.h"
#endif

namespace ib {

namespace {
struct Entry {
  const char* name;
  std::unique_ptr<Simulator> (*make)();
};
const Entry kSimulators[] = {
    {"reference", make_reference_simulator},
#if IMPACTBENCH_WITH_MUJOCO
    {"mujoco", make_mujoco_simulator},
#endif
#if IMPACTBENCH_WITH_ODE
    {"ode", make_ode_simulator},
#endif
#if IMPACTBENCH_WITH_BULLET
    {"bullet", make_bullet_simulator},
#endif
};
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
    return c;
  }();
  return catalog;
}

std::vector<std::string> simulator_names() { return simulator_catalog().names; }

std::unique_ptr<Simulator> make_simulator(const std::string& name) { return simulator_catalog().make(name); }

}  // namespace ib
