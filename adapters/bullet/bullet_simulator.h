// Bullet 3.24 (double precision) behind the one Simulator interface: the linked-body rig of rig.md
// section 4 as a btMultiBody chain or as rigid bodies joined by spring constraints, with the contact
// between the tips made by Bullet (matched to the law, or Bullet's defaults) or injected by the harness.
// Options, mapping and measured behaviour: adapters/bullet/README.md.
#pragma once

#include <memory>

#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_bullet_simulator();

}  // namespace ib
