// How the contact between the tips is produced in ODE for each path and law (adapter_options.h):
//  matched  - spring-dashpot: ODE's contact joint softened by soft_constraint(k, c, h) (backward Euler,
//             compressive only); Newton: ODE's contact joint with dContactBounce (bounce = e);
//             Hertz: ODE has no nonlinear contact, so the law's force from the tip states, applied at
//             the tips (the same computation as the injected path);
//  injected - every law's force from the tip states (InjectedContact), ODE's collision switched off;
//  native   - ODE's contact joint as a user leaves it: no soft ERP/CFM (the world's ERP 0.2 and
//             CFM 1e-10), no bounce: a hard, inelastic contact whatever the law.
// Every ODE contact here is frictionless (mu = 0): the rig has no friction (rig.md).
#pragma once

#include <ode/ode.h>

#include <string>

#include "model/simulator_options.h"
#include "physics/contact_laws.h"

namespace ib::ode {

// dContactBounce acts only when the closing speed exceeds this; slower impacts are plastic. Small
// against the rig's impacts (0.01 to 0.3 m/s) and >= 0 (a negative threshold disables bounce, engines.md).
constexpr double kBounceThreshold_m_s = 1e-4;

struct ContactSetup {
  bool ode_collision = false;          // ODE collides the tip spheres and makes a contact joint
  dSurfaceParameters surface{};        // that joint's surface
  bool force_from_tip_states = false;  // the law's force is computed from the tips and applied to them
};

ContactSetup contact_setup(ContactPath path, const ContactModel& law, double time_step_s);

}  // namespace ib::ode
