// The ODE adapter behind the one Simulator interface: the rig of rig.md section 4 in ODE 0.16.2
// (double precision), with the contact paths matched, injected and native (see ode_contact.h and
// README.md). Options: see option_help().
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_ode_simulator();

}  // namespace ib
