// An instantaneous impact (event_solver.h): Newton's restitution as an impulse on the modal velocities, and
// sticking when the tips cannot separate.
#include "reference/event_solver.h"

namespace ib::reference_internal {

// ---- Newton impacts ---------------------------------------------------------------------------
// Applies the impulse at an onset; returns true when the impacts accumulate and the tips stick.
bool Solver::newton_impact(double t, ModalState& x) {
  const double e = std::get<NewtonLaw>(model_.contact).restitution;
  const Eigen::VectorXd& b = model_.contact_lever;
  const double approach = std::max(0.0, b.dot(x.v));
  const double impulse = (1 + e) * approach / lever_norm2_;
  x.v -= b * impulse;
  const double meff = 1 / lever_norm2_;
  solution_.energy.contact_dissipation_j += 0.5 * meff * (1 - e * e) * approach * approach;
  ContactEvent event;
  event.onset_time_s = event.end_time_s = t;
  event.approach_velocity_m_s = approach;
  event.rebound_velocity_m_s = e * approach;
  event.restitution = approach > 0 ? e : 0;
  event.peak_force_n = std::numeric_limits<double>::quiet_NaN();
  event.impulse_n_s = impulse;
  event.max_indentation_m = 0;
  ++solution_.impacts;
  // Relative acceleration with no contact force: > 0 pushes the tips back together.
  const TipState s = tip_state(x.q.data(), x.v.data(), t, Phase::free);
  const double closing_acc = model_.contact_lever.dot(acceleration_without_contact(x, t));
  const double rebound = -s.indentation_rate;
  bool accumulate = false;
  if (closing_acc > 0) {
    // A bouncing tip under constant closing acceleration stops after sum 2 e^k v / a = 2 v / ((1 - e) a).
    accumulate = e < 1 && 2 * rebound / ((1 - e) * closing_acc) < settings_.accumulation_time_s;
  }
  if (accumulate) {
    const double plastic = b.dot(x.v) / lever_norm2_;  // removes the remaining rebound velocity
    x.v -= b * plastic;
    solution_.energy.contact_dissipation_j += 0.5 * meff * rebound * rebound;
    event.impulse_n_s += plastic;
    event.rebound_velocity_m_s = 0;
    event.restitution = 0;
    stick_impulse_ = event.impulse_n_s;
  }
  solution_.trajectory.events.push_back(event);
  return accumulate;
}

}  // namespace ib::reference_internal
