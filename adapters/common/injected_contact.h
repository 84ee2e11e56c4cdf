// The injected contact path: the harness computes the contact law's force from the tip states at the
// start of each step and the adapter applies it (-F on frame 1's tip, +F on frame 2's, along x), so
// that an engine's time stepping can be told apart from its contact model. The same code for every
// engine; the law is the reference's own (physics/contact_laws.h).
#pragma once

#include "adapters/common/rig.h"

namespace ib {

class InjectedContact {
 public:
  explicit InjectedContact(const RigSpec& rig);

  // The compressive force [N] to apply over the coming step of length h, from the tip displacements
  // [m] and velocities [m/s] at its start. Compliant laws: the law's force at delta = u1 - u2 - gap.
  // Newton: when the tips close through contact, the impulse (1 + e) m_eff delta' that reverses the
  // closing speed with factor e (m_eff: the chains' linearised tip effective mass), spread over the
  // step; once per contact.
  double force(double u1, double v1, double u2, double v2, double h);

 private:
  ContactModel law_;
  double gap_m_, effective_mass_kg_;
  bool impacted_ = false;  // Newton: the current contact has had its impulse
};

}  // namespace ib
