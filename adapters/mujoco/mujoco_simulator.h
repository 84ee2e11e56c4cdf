// The rig of rig.md section 4 in MuJoCo 2.2.2 behind the Simulator interface (engine name "mujoco").
// See README.md in this folder for the mapping of every physical parameter, the contact paths and the
// options.
#pragma once

#include <memory>
#include <string>

#include "adapters/mujoco/mujoco_contact_mapping.h"
#include "model/simulator.h"

namespace ib {

std::unique_ptr<Simulator> make_mujoco_simulator();

// The MJCF of exactly the model a run with these settings builds (options included), with comments
// naming the physical values; it compiles with mj_loadXML from a file and opens in MuJoCo's viewer.
// The motor and any harness-applied contact force are described in comments (MJCF cannot express
// them). Throws std::invalid_argument for settings a run would reject.
std::string mujoco_model_xml(const Scenario& scenario, const RunSettings& settings);

}  // namespace ib
