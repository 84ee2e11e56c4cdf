// The Simbody adapter (adapters/simbody/README.md): the rig of rig.md section 4 in Simbody 3.7.
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_simbody_simulator();

}  // namespace ib
