#include "adapters/dart/dart_contact.h"

#include <cmath>
#include <variant>

namespace ib::dart_adapter {

ContactSetup contact_setup(ContactPath path, const ContactModel& law) {
  ContactSetup setup;
  switch (path) {
    case ContactPath::injected:
      setup.force_from_tip_states = true;
      break;
    case ContactPath::native:
      setup.collision = Collision::fcl_default;  // DART's restitution (0) and friction (1) left as they are
      break;
    case ContactPath::matched:
      if (const auto* newton = std::get_if<NewtonLaw>(&law)) {
        setup.collision = Collision::analytic;
        setup.restitution_per_shape = std::sqrt(newton->restitution);  // the pair's value is the product
        setup.friction = 0.0;
      } else {
        setup.force_from_tip_states = true;  // no compliant contact for rigid bodies in DART
      }
      break;
  }
  return setup;
}

}  // namespace ib::dart_adapter
