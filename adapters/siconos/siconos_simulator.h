// The Siconos adapter (adapters/siconos/README.md): the rig of rig.md section 4 as two linear Lagrangian
// systems stepped by Moreau-Jean time stepping, the nonsmooth scheme of the vibro-impact field.
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_siconos_simulator();

}  // namespace ib
