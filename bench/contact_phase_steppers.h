// One compliant contact phase, from its onset to the separation, integrated with one of several Boost.Odeint
// steppers (bench/contact_integrators.cpp compares them at equal accuracy).
//
// Steppers with dense output (dopri5, bulirsch_stoer_dense_out, rosenbrock4) end the phase as
// reference/contact_phase.cpp does: the separation located on the dense output (TOMS 748, after the last
// interior maximum of delta), the peak force at the root of dF/dt on it. dopri5 and rosenbrock4 then retake
// the last step exactly to the separation, as the reference does with Dormand-Prince; Bulirsch-Stoer's
// dense output has its interpolation error controlled and is read there directly.
// The controlled-only steppers (cash_karp54, fehlberg78) have no dense output in odeint: the separation is
// found by Newton's method on delta, each iterate a retaken step from the last accepted state (delta and
// delta' both come out of that step), started from the cubic Hermite guess; the peak force is read from
// one retaken step at the maximum of the cubic Hermite of F through the step's ends.
#pragma once

#include <string>

#include "bench/contact_phase_system.h"

namespace ib::bench {

enum class ContactStepper { dopri5, cash_karp54, fehlberg78, bulirsch_stoer, rosenbrock4 };
const char* to_string(ContactStepper stepper);
ContactStepper contact_stepper_from_string(const std::string& name);  // throws std::invalid_argument

// Where a contact phase starts: the onset time and the modal state there (delta = 0, closing).
struct ContactOnset {
  double t_s = 0;
  ModalState state;
};

// What the phase gave: the figures the reference records of a contact episode, and what it cost.
struct ContactOutcome {
  double duration_s = 0;
  double rebound_velocity_m_s = 0;  // -delta' at separation
  double impulse_n_s = 0;           // integral of F_c over the phase
  double peak_force_n = 0;
  long long steps = 0;  // accepted steps
  long long rhs_calls = 0, jacobian_calls = 0;
};

struct StepperTolerance {
  double relative = 1e-9;
  double absolute = 1e-12;  // on modal coordinates [sqrt(kg) m, sqrt(kg) m/s] and the ledger's integrals
};

// max_step_s: the reference's largest step (its scan grid step), so that extrema stay one per step.
ContactOutcome integrate_contact_phase(const ContactPhaseSystem& system, ContactStepper stepper,
                                       const StepperTolerance& tolerance, double max_step_s, const ContactOnset& onset);

}  // namespace ib::bench
