// The simulators built into this binary. An engine adapter adds itself here when CMake finds its library.
#include "reference_simulator.h"
#include "simulator.h"

namespace ib {

std::vector<std::string> simulator_names() { return {"reference"}; }

std::unique_ptr<Simulator> make_simulator(const std::string& name) {
  if (name == "reference") return make_reference_simulator();
  return nullptr;
}

}  // namespace ib
