// How a DART run makes the tips' contact, per path and law, in one place (README.md, "Contact paths").
// DART 6.12 has only rigid contact for rigid bodies: a velocity-level LCP with Newton restitution (per
// shape; a pair uses the product of its two values) and, hard-coded in ContactConstraint.cpp, a bounce
// threshold: an impact whose rebound speed e * v would be at most 0.1 model units per second gets no
// bounce at all, and a rebound above 100 model units per second is capped there.
//   matched Newton: analytic sphere-sphere collision (DARTCollisionDetector), restitution sqrt(e) on each
//     tip sphere, no friction (the tips meet head-on; friction would only add two rows to the LCP).
//   matched Hertz and spring-dashpot: DART has no compliant contact for rigid bodies, and its error
//     reduction and constraint force mixing cannot be tuned into one (both are process-wide constants,
//     the mixing is relative to the LCP's diagonal and the error-reduction velocity is capped at 1e-3
//     model units per second): the law's force from the tip states, as on the injected path.
//   injected: the harness's law as tip forces; DART detects no collision.
//   native: DART as a user leaves it: its default detector (FCL, spheres as meshes), restitution 0,
//     friction 1. The scenario's law is not used.
#pragma once

#include <optional>

#include "adapters/common/rig.h"
#include "adapters/dart/dart_rig.h"
#include "model/simulator_options.h"

namespace ib::dart_adapter {

// DART's hard-coded contact velocities (ContactConstraint.cpp, DART 6.12.1), in model units per second:
// divided by the length scale they are in m/s. Measured in tests/dart_contact_test.cpp.
constexpr double kBounceThreshold_units_s = 0.1;    // DART_BOUNCING_VELOCITY_THRESHOLD
constexpr double kMaxBounceVelocity_units_s = 100;  // DART_MAX_BOUNCING_VELOCITY

struct ContactSetup {
  bool force_from_tip_states = false;  // the harness's law applied as tip forces
  Collision collision = Collision::none;
  std::optional<double> restitution_per_shape;
  std::optional<double> friction;
};

ContactSetup contact_setup(ContactPath path, const ContactModel& law);

}  // namespace ib::dart_adapter
