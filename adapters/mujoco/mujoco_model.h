// What one MuJoCo run builds, decided from the scenario and the run settings in one place (options,
// chain, contact path and its parameters), and the MJCF text of that model. The simulator compiles
// exactly this text, and `impactbench export --engine mujoco` writes it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adapters/common/rig.h"
#include "adapters/mujoco/mujoco_contact_mapping.h"
#include "model/simulator.h"
#include "model/simulator_options.h"

namespace ib {

enum class MujocoIntegrator { euler, rk4 };

// when RunSettings::time_step_s is 0: descriptor.json's default_time_step_s, which the adapter is compiled with
// (adapters/CMakeLists.txt), defined in mujoco_model.cpp
extern const double kDefaultMujocoTimeStep_s;
constexpr int kDefaultNewtonContactSteps = 4;  // matched Newton: steps the contact force lasts (README)

// The tip-to-tip contact MuJoCo computes itself through a <pair> with a direct solref (matched path,
// spring-dashpot and Newton laws): the spring-dashpot it is set to and MuJoCo's form of it.
struct TipPairContact {
  SpringDashpot spring_dashpot;     // what the contact is meant to be [N/m, N s/m]
  double invweight_sum_per_kg = 0;  // body_invweight0 (translation) of the two tip bodies, summed [1/kg]
  SolrefSolimp parameters;
  double newton_damping_ratio = 0;  // Newton only: the contact's damping ratio on the tips' effective mass [-]
  double newton_duration_s = 0;     // Newton only: how long its force lasts [s]
};

struct MujocoRunPlan {
  std::string scenario_name;
  ContactLaw law = ContactLaw::hertz;
  RigSpec rig;
  int links = 0;
  ContactPath path = ContactPath::matched;
  MujocoIntegrator integrator = MujocoIntegrator::euler;
  double time_step_s = kDefaultMujocoTimeStep_s;
  std::optional<TipPairContact> tip_pair;  // MuJoCo's contact set to the law (matched spring-dashpot, Newton)
  bool harness_contact_force = false;      // the harness applies the law's force (injected; matched Hertz)
  bool native_contact = false;             // MuJoCo's default contact between the tip spheres
};

// The options the adapter takes, with a line each.
const std::vector<std::pair<std::string, std::string>>& mujoco_options();

// The chain's K for a run: option "links", or default_links(scenario).
int mujoco_chain_links(const Scenario& scenario, const RunSettings& settings);

// Reads the options (std::invalid_argument when one is wrong), builds the rig and, for the matched
// spring-dashpot and Newton paths, maps the contact to solref/solimp (this compiles the model once
// to read MuJoCo's body_invweight0).
MujocoRunPlan plan_mujoco_run(const Scenario& scenario, const RunSettings& settings);

// The MJCF of the plan: radians, SI units, comments naming the physical values.
std::string write_mjcf(const MujocoRunPlan& plan);

// Names the simulator looks up in the compiled model.
std::string mujoco_body_name(int frame, int link);   // "frame1_link3" (frame and link from 0)
std::string mujoco_joint_name(int frame, int link);  // "frame1_hinge3"
std::string mujoco_tip_site_name(int frame);         // "frame1_tip"
std::string mujoco_tip_geom_name(int frame);         // "frame1_tip_sphere"

}  // namespace ib
