#include "adapters/common/injected_contact.h"

namespace ib {

InjectedContact::InjectedContact(const RigSpec& rig)
    : law_(rig.law), gap_m_(rig.gap_m), effective_mass_kg_(rig.contact_effective_mass_kg) {}

double InjectedContact::force(double u1, double v1, double u2, double v2, double h) {
  const double delta = u1 - u2 - gap_m_, rate = v1 - v2;
  if (const auto* newton = std::get_if<NewtonLaw>(&law_)) {
    if (delta < 0) {
      impacted_ = false;
      return 0;
    }
    if (impacted_ || rate <= 0) return 0;
    impacted_ = true;
    return (1 + newton->restitution) * effective_mass_kg_ * rate / h;
  }
  return contact_force(law_, delta, rate);
}

}  // namespace ib
