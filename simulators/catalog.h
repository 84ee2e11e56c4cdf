// The one place that knows the list of simulators of this binary: the reference and each engine CMake
// found and built (adapters/CMakeLists.txt defines IMPACTBENCH_WITH_<ENGINE>), their names, factories and
// the pairing of an engine's chain with the reference on that chain. The harness receives it from the
// command line's wiring (cli/) and never includes this file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/simulator.h"

namespace ib {

const SimulatorCatalog& simulator_catalog();

// Shorthands for simulator_catalog().names and .make.
std::vector<std::string> simulator_names();
std::unique_ptr<Simulator> make_simulator(const std::string& name);  // nullptr when unknown

}  // namespace ib
