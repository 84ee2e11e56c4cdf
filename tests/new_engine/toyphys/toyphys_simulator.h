// A toy engine behind the one Simulator interface, to show what a new engine adds (tests/new_engine/).
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_toyphys_simulator();

}  // namespace ib
