// The simulators built into this binary: the reference, and each engine CMake found and built
// (adapters/CMakeLists.txt defines IMPACTBENCH_WITH_<ENGINE>).
#include "reference_simulator.h"
#include "simulator.h"

#if IMPACTBENCH_WITH_MUJOCO
#include "mujoco_simulator.h"
#endif
#if IMPACTBENCH_WITH_ODE
#include "ode_simulator.h"
#endif
#if IMPACTBENCH_WITH_BULLET
#include "bullet_simulator.h"
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

std::vector<std::string> simulator_names() {
  std::vector<std::string> names;
  for (const Entry& e : kSimulators) names.push_back(e.name);
  return names;
}

std::unique_ptr<Simulator> make_simulator(const std::string& name) {
  for (const Entry& e : kSimulators)
    if (name == e.name) return e.make();
  return nullptr;
}

}  // namespace ib
