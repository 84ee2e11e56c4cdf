// The reference behind the one Simulator interface: options in RunSettings::options select the mode
// set and the integrator's accuracy (see option_help()).
#pragma once

#include <memory>

#include "model/simulator.h"
#include "reference/reference_solver.h"

namespace ib {

// The reference settings a run's options ask for; throws std::invalid_argument naming the option,
// the value and what is allowed.
ReferenceSettings reference_settings_from_options(const std::map<std::string, std::string>& options);

std::unique_ptr<Simulator> make_reference_simulator();

// The options that make the reference run on the K-link chain an engine builds (rig.md section 4), so
// that the engine is scored against exactly the system it simulates. The one place that spells them.
// chain_reference_options is the chain with the default damping (modal, what an engine builds unless its
// option chain_damping says otherwise); ..._with_damping names it (written only when not the default,
// so that the default's options, and the reference cache's keys, are those of before the option).
std::map<std::string, std::string> chain_reference_options(int links);
std::map<std::string, std::string> chain_reference_options_with_damping(int links, ChainDamping damping);

}  // namespace ib
