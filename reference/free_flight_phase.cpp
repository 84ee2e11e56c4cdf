// Free flight (event_solver.h): the closed-form motion between contacts, scanned on a grid for the next
// onset, which is then located to full precision.
#include "reference/event_solver.h"

namespace ib::reference_internal {

// Advances in closed form until a contact onset (returns true, t and x at the onset) or the end
// of the run (returns false). after_contact: t is where a contact ended, so delta(t) is zero and
// a re-contact counts only after the tips have really moved apart.
bool Solver::free_flight(double& t, ModalState& x, bool after_contact) {
  Gap ga = gap_of(x, t);
  FreeFlight::MotorPhase phase_a = flight_.motor_phase(t);
  bool first = true;
  double* work = settings_.track_energy ? &solution_.energy.motor_work_j : nullptr;
  double* dissipation = settings_.track_energy ? &solution_.energy.structural_dissipation_j : nullptr;
  double fine_until = after_contact ? t + coarse_step_ : t;  // no coarse step right after a contact
  TipState tips_a;
  bool tips_a_valid = false;
  // Consecutive samples within one flight follow from the previous one by the precomputed
  // transition over the sample interval, instead of a fresh transition (exp, sin and cos of every
  // mode) from the grid point. Sample times are one interval apart up to rounding (~1e-16 s).
  double last_sample_t = -kInf;
  FreeFlight::MotorPhase last_sample_phase;
  auto sample_at = [&](double ts, const ModalState& x_grid, double t_grid) {
    const FreeFlight::MotorPhase phase = flight_.motor_phase(ts);
    if (std::abs(ts - last_sample_t - sample_transition_.tau_s) <= 1e-9 * sample_transition_.tau_s) {
      flight_.advance(sample_transition_, last_sample_phase, phase, x_sample_, xs_);
      std::swap(x_sample_, xs_);
    } else {
      flight_.advance(x_grid, t_grid, ts - t_grid, x_sample_);
    }
    last_sample_t = ts;
    last_sample_phase = phase;
    return tip_state(x_sample_.q.data(), x_sample_.v.data(), ts, Phase::free);
  };
  while (t < end_time_) {
    if (coarse_step_ > 0 && t >= fine_until && t + coarse_step_ < end_time_ && !recorder_.wants(t + coarse_step_)) {
      if (coarse_step_without_contact(t, x, phase_a, work, dissipation)) {
        ga = gap_of(x, t);
        first = false;
        continue;
      }
      fine_until = t + coarse_step_;  // a contact may start: scan this stretch on the fine grid
    }
    const double t0 = t;
    const bool standard = grid_step_ < end_time_ - t0;
    const double tb = standard ? t0 + grid_step_ : end_time_;
    const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
    double step_work = 0, step_dissipation = 0;  // energy over a full grid step, kept if no onset cuts it
    if (standard) {
      flight_.advance(grid_transition_, phase_a, phase_b, x, xb_, work ? &grid_energy_ : nullptr, &step_work,
                      &step_dissipation);
    } else {
      flight_.advance(x, t0, tb - t0, xb_);
    }
    const Gap gb = gap_of(xb_, tb);
    ++solution_.grid_intervals;
    auto gap_at = [&](double ts) {
      flight_.advance(x, t0, ts - t0, xs_);
      return gap_of(xs_, ts);
    };
    const double onset = find_onset(ga, gb, gap_at, first && after_contact);
    first = false;
    const double t_end = onset < kInf ? onset : tb;
    ModalState& x_end = onset < kInf ? x_onset_ : xb_;
    if (onset < kInf) flight_.advance(x, t0, onset - t0, x_onset_);
    if (recorder_.wants(t_end)) {
      auto eval = [&](double ts) {
        flight_.advance(x, t0, ts - t0, xs_);
        return tip_state(xs_.q.data(), xs_.v.data(), ts, Phase::free);
      };
      // the start's kinematics carry over from the previous step when it was recorded too
      if (!(tips_a_valid && tips_a.t == t0)) tips_a = tip_state(x.q.data(), x.v.data(), t0, Phase::free);
      const TipState tips_b = tip_state(x_end.q.data(), x_end.v.data(), t_end, Phase::free);
      record_interval(tips_a, tips_b, eval, [&](double ts) { return sample_at(ts, x, t0); });
      tips_a = tips_b;
      tips_a_valid = true;
    }
    if (work) {
      if (standard && onset == kInf) {
        *work += step_work;
        *dissipation += step_dissipation;
      } else {  // a cut step: its own integrals (the scratch state receives a discarded copy)
        const FreeFlight::EnergyForms forms = flight_.energy_forms(t_end - t0);
        flight_.advance(flight_.transition(t_end - t0), phase_a, flight_.motor_phase(t_end), x, xs_, &forms, work,
                        dissipation);
      }
    }
    t = t_end;
    std::swap(x, x_end);
    if (onset < kInf) return true;
    ga = gb;
    phase_a = phase_b;
  }
  return false;
}

// Takes one coarse step if no contact can start within it: the slow modes' indentation (resolved by
// the coarse step, its interior maximum located) plus the bound on the fast modes stays negative.
bool Solver::coarse_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double* work,
                                 double* dissipation) {
  const double t0 = t, tb = t + coarse_step_;
  const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
  const double fast = flight_.displacement_bound(x, phase_a, fast_lever_, 0, m_);
  double step_work = 0, step_dissipation = 0;
  flight_.advance(coarse_transition_, phase_a, phase_b, x, xb_, work ? &coarse_energy_ : nullptr, &step_work,
                  &step_dissipation);
  auto slow_delta = [&](const ModalState& s) { return slow_lever_.dot(s.q) - model_.gap_m; };
  double highest = std::max(slow_delta(x), slow_delta(xb_));
  const double rate_a = slow_lever_.dot(x.v), rate_b = slow_lever_.dot(xb_.v);
  if (rate_a > 0 && rate_b < 0) {
    auto rate_at = [&](double ts) {
      flight_.advance(x, t0, ts - t0, xs_);
      return slow_lever_.dot(xs_.v);
    };
    const double c = find_root(rate_at, t0, tb, rate_a, rate_b, kExtremumBits);
    flight_.advance(x, t0, c - t0, xs_);
    highest = std::max(highest, slow_delta(xs_));
  }
  if (highest + fast >= 0) return false;
  ++solution_.coarse_intervals;
  if (work) *work += step_work, *dissipation += step_dissipation;
  t = tb;
  std::swap(x, xb_);
  phase_a = phase_b;
  return true;
}

}  // namespace ib::reference_internal
