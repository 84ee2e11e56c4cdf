// Compliant contact and sticking (event_solver.h): the modal equations with the contact force, integrated
// with Dormand-Prince until the tips separate.
#include "reference/event_solver.h"

namespace ib::reference_internal {

template <class Eval>
void Solver::record_interval(const TipState& sa, const TipState& sb, Eval&& eval) {
  if (!recorder_.wants(sb.t)) return;
  std::array<TipState, 3> points;  // at most one extremum each of a1, a2 and F_c
  int count = 0;
  for (int f = 0; f < 2; ++f) {
    if (sa.jerk[f] * sb.jerk[f] < 0) {
      const double c =
          find_root_after([&](double t) { return eval(t).jerk[f]; }, sa.t, sb.t, sa.jerk[f], sb.jerk[f], kExtremumBits);
      points[count++] = eval(c);
    }
  }
  if (sa.force_rate * sb.force_rate < 0) {
    const double c = find_root_after([&](double t) { return eval(t).force_rate; }, sa.t, sb.t, sa.force_rate,
                                     sb.force_rate, kExtremumBits);
    points[count++] = eval(c);
  }
  for (int i = 1; i < count; ++i)  // insertion sort by time: at most three points
    for (int j = i; j > 0 && points[j].t < points[j - 1].t; --j) std::swap(points[j], points[j - 1]);
  int next = 0;
  for (double ts = recorder_.next_sample_time(); ts <= sb.t; ts = recorder_.next_sample_time()) {
    while (next < count && points[next].t <= ts) recorder_.feed(points[next++]);
    recorder_.sample(ts == sb.t ? sb : eval(ts));
  }
  while (next < count) recorder_.feed(points[next++]);
  recorder_.feed(sb);
}

// Peak force and maximum indentation of a contact episode, exact between steps.
template <class Eval>
void Solver::track_event(ContactEvent& event, const TipState& sa, const TipState& sb, Eval&& eval) const {
  event.peak_force_n = std::max({event.peak_force_n, sa.force, sb.force});
  event.max_indentation_m = std::max({event.max_indentation_m, sa.indentation, sb.indentation});
  if (sa.force_rate > 0 && sb.force_rate < 0) {
    const double c = find_root_after([&](double t) { return eval(t).force_rate; }, sa.t, sb.t, sa.force_rate,
                                     sb.force_rate, kExtremumBits);
    event.peak_force_n = std::max(event.peak_force_n, eval(c).force);
  }
  if (sa.indentation_rate > 0 && sb.indentation_rate < 0) {
    const double c = find_root_after([&](double t) { return eval(t).indentation_rate; }, sa.t, sb.t,
                                     sa.indentation_rate, sb.indentation_rate, kExtremumBits);
    event.max_indentation_m = std::max(event.max_indentation_m, eval(c).indentation);
  }
}

// ---- compliant contact and sticking -----------------------------------------------------------
// Integrates a contact phase with Dormand-Prince until it ends (separation, or release from
// sticking) or the run ends. Returns false when the run cannot go on (status set).
// The contact phase's equations: the modes under the motor, their damping and the contact force, and the
// integrals the phase adds up (motor work, structural and contact dissipation, impulse).
void Solver::contact_rates(const OdeState& s, OdeState& ds, double ts, Phase phase) const {
  const double motor = model_.motor ? model_.motor->at(ts) : 0;
  const ContactState k = contact_state(s.data(), s.data() + m_, motor, phase);
  const Eigen::Map<const Eigen::ArrayXd> q(s.data(), m_), v(s.data() + m_, m_);
  Eigen::Map<Eigen::ArrayXd> dq(ds.data(), m_), dv(ds.data() + m_, m_);
  dq = v;
  dv = model_.motor_lever.array() * motor - two_zeta_omega_ * v - omega2_ * q - model_.contact_lever.array() * k.force;
  ds[2 * m_] = model_.motor ? motor * model_.motor_lever.dot(Eigen::Map<const Eigen::VectorXd>(s.data() + m_, m_)) : 0;
  ds[2 * m_ + 1] = structural_power(s.data() + m_);
  ds[2 * m_ + 2] = (k.force - elastic_contact_force(model_.contact, k.indentation)) * k.indentation_rate;
  ds[2 * m_ + 3] = k.force;
}

// A contact episode lasts while the tips exchange a force: a clipped law's force can end before the overlap
// does (the tips part faster than the spring relaxes), and the episode with it. Between the tips sa and sb (the
// step from ta): where and at what opening speed the force ended, kept until the phase ends.
template <class Eval>
void Solver::track_force_end(const TipState& sa, const TipState& sb, double ta, Eval&& eval) {
  if (sa.force > 0 && sb.force == 0) {
    auto unclipped = [&](double s) {
      const TipState k = eval(s);
      return contact_force_unclipped(model_.contact, k.indentation, k.indentation_rate);
    };
    const double end = find_root(unclipped, ta, sb.t, unclipped(ta), unclipped(sb.t));
    force_end_ = {end, -eval(end).indentation_rate};
  } else if (sb.force != 0) {
    force_end_.reset();
  }
}

bool Solver::integrate_contact(double& t, ModalState& x, Phase phase) {
  OdeState y(2 * m_ + 4, 0.0);
  std::copy(x.q.data(), x.q.data() + m_, y.begin());
  std::copy(x.v.data(), x.v.data() + m_, y.begin() + m_);
  auto rhs = [&](const OdeState& s, OdeState& ds, double ts) { contact_rates(s, ds, ts, phase); };
  // The integrator's step never exceeds the scan grid, so extrema stay one per step.
  auto dense =
      odeint::make_dense_output(settings_.absolute_tolerance, settings_.relative_tolerance, grid_step_, Dopri());
  dense.initialize(y, t, std::min(grid_step_, 1e-6));
  TipState sa = tip_state(y.data(), y.data() + m_, t, phase);
  ContactEvent event;
  event.onset_time_s = t;
  event.approach_velocity_m_s = sa.indentation_rate;
  event.impulse_n_s = phase == Phase::sticking ? stick_impulse_ : 0;
  event.peak_force_n = sa.force;
  event.max_indentation_m = std::max(0.0, sa.indentation);
  OdeState ys(y.size());
  auto eval = [&](double ts) {
    dense.calc_state(ts, ys);
    return tip_state(ys.data(), ys.data() + m_, ts, phase);
  };
  // The quantity whose sign change ends the phase: delta for a compliant contact, F_c for sticking.
  auto ending = [&](const TipState& s) { return phase == Phase::compliant ? s.indentation : s.force; };
  while (true) {
    try {
      dense.do_step(rhs);
    } catch (const std::exception& error) {
      fail(RunStatus::failed,
           std::string("reference integrator failed at t = ") + std::to_string(t) + " s: " + error.what());
      return false;
    }
    ++solution_.integrator_steps;
    const double ta = dense.previous_time(), tb = dense.current_time();
    const OdeState& yb = dense.current_state();
    if (!std::isfinite(yb[0]) || !std::isfinite(yb[m_])) {
      fail(RunStatus::failed, "reference integrator produced a non-finite state at t = " + std::to_string(tb) + " s");
      return false;
    }
    TipState sb = tip_state(yb.data(), yb.data() + m_, tb, phase);
    double t_stop = tb;
    bool ended = false;
    if (ending(sb) < 0) {
      // Locate the end on the dense output, after the last interior maximum of the ending quantity.
      double lo = ta, f_lo = ending(sa);
      if (f_lo <= 0) {
        const double c = phase == Phase::compliant ? find_root([&](double s) { return eval(s).indentation_rate; }, ta,
                                                               tb, sa.indentation_rate, sb.indentation_rate)
                                                   : ta;
        lo = c;
        f_lo = ending(eval(c));
      }
      t_stop = f_lo > 0 ? find_root([&](double s) { return ending(eval(s)); }, lo, tb, f_lo, ending(sb)) : lo;
      ended = true;
    }
    if (t_stop > end_time_) t_stop = end_time_, ended = false;
    OdeState y_stop = yb;
    if (t_stop < tb) {
      // Retake the step exactly to the stop time: the force is smooth on [ta, t_stop].
      Dopri().do_step(rhs, dense.previous_state(), ta, y_stop, t_stop - ta);
      sb = tip_state(y_stop.data(), y_stop.data() + m_, t_stop, phase);
    }
    record_interval(sa, sb, eval);
    track_event(event, sa, sb, eval);
    if (phase == Phase::compliant) track_force_end(sa, sb, ta, eval);
    if (ended || t_stop >= end_time_) {
      t = t_stop;
      close_contact_phase(t, y_stop, sb, event, phase, x);
      return true;
    }
    sa = sb;
  }
}

void Solver::close_contact_phase(double t, const OdeState& y_stop, const TipState& tips_stop, ContactEvent& event,
                                 Phase phase, ModalState& x) {
  x.q = Eigen::Map<const Eigen::VectorXd>(y_stop.data(), m_);
  x.v = Eigen::Map<const Eigen::VectorXd>(y_stop.data() + m_, m_);
  if (phase == Phase::sticking) project_onto_contact(x);
  solution_.energy.motor_work_j += y_stop[2 * m_];
  solution_.energy.structural_dissipation_j += y_stop[2 * m_ + 1];
  solution_.energy.contact_dissipation_j += y_stop[2 * m_ + 2];
  event.end_time_s = force_end_ ? force_end_->first : t;
  event.impulse_n_s += y_stop[2 * m_ + 3];
  event.rebound_velocity_m_s = force_end_ ? force_end_->second : -tips_stop.indentation_rate;
  force_end_.reset();
  event.restitution = event.approach_velocity_m_s > 0 ? event.rebound_velocity_m_s / event.approach_velocity_m_s : 0;
  if (phase != Phase::sticking) {
    ++solution_.impacts;
    solution_.trajectory.events.push_back(event);
    return;
  }
  ++solution_.sticking_phases;
  // the sticking phase continues the impact episode that started it. Held at delta' = 0 and released where
  // the holding force would turn tensile, the tips part with zero relative speed: what the state shows there
  // is rounding (about 1e-17 m/s, of either sign).
  ContactEvent& start = solution_.trajectory.events.back();
  start.end_time_s = event.end_time_s;
  start.impulse_n_s = event.impulse_n_s;
  start.peak_force_n = event.peak_force_n;
  start.rebound_velocity_m_s = std::max(0.0, event.rebound_velocity_m_s);
  // rebound over the approach of the impact that started the episode (the sticking phase's own "approach" is
  // the rounding left after the plastic impulse)
  start.restitution = start.approach_velocity_m_s > 0 ? start.rebound_velocity_m_s / start.approach_velocity_m_s : 0;
}

}  // namespace ib::reference_internal
