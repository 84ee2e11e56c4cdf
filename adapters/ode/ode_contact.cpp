#include "adapters/ode/ode_contact.h"

#include <variant>

#include "adapters/ode/soft_constraint.h"

namespace ib::ode {

ContactSetup contact_setup(ContactPath path, const ContactModel& law, double time_step_s) {
  ContactSetup setup;
  setup.surface.mu = 0;  // frictionless: only the normal row
  switch (path) {
    case ContactPath::injected:
      setup.force_from_tip_states = true;
      return setup;
    case ContactPath::native:
      setup.ode_collision = true;
      setup.surface.mode = 0;
      return setup;
    case ContactPath::matched:
      break;
  }
  if (const auto* spring = std::get_if<ViscoelasticLaw>(&law)) {
    const SoftConstraint soft = soft_constraint(spring->stiffness_n_per_m, spring->damping_n_s_per_m, time_step_s);
    setup.ode_collision = true;
    setup.surface.mode = dContactSoftERP | dContactSoftCFM;
    setup.surface.soft_erp = soft.erp;
    setup.surface.soft_cfm = soft.cfm;
  } else if (const auto* newton = std::get_if<NewtonLaw>(&law)) {
    setup.ode_collision = true;
    // The rebound is the bounce alone: no error reduction (ERP 0) pushing the overlapping spheres apart
    // on top of it; the world's CFM (1e-10) keeps the row hard.
    setup.surface.mode = dContactBounce | dContactSoftERP;
    setup.surface.soft_erp = 0;
    setup.surface.bounce = newton->restitution;
    setup.surface.bounce_vel = kBounceThreshold_m_s;
  } else {
    setup.force_from_tip_states = true;  // Hertz
  }
  return setup;
}

}  // namespace ib::ode
