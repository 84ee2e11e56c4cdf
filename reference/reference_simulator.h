// The reference behind the one Simulator interface: options in RunSettings::options select the mode
// set and the integrator's accuracy (see option_help()).
#pragma once

#include <memory>

#include "reference/reference_solver.h"
#include "model/simulator.h"

namespace ib {

// The reference settings a run's options ask for; throws std::invalid_argument naming the option,
// the value and what is allowed.
ReferenceSettings reference_settings_from_options(const std::map<std::string, std::string>& options);

std::unique_ptr<Simulator> make_reference_simulator();

// The options that make the reference run on the K-link chain an engine builds (rig.md section 4), so
// that the engine is scored against exactly the system it simulates. The one place that spells them.
std::map<std::string, std::string> chain_reference_options(int links);

}  // namespace ib
