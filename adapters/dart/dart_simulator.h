// The DART adapter behind the one Simulator interface: the rig of rig.md section 4 in DART 6.12.1
// (double precision; its core library only, never its single-precision Bullet collision component), with
// the contact paths matched, injected and native (dart_contact.h, README.md). Options: option_help().
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_dart_simulator();

}  // namespace ib
