#include "reference/reference_solver.h"

#include "reference/event_solver.h"

namespace ib {

double EnergyLedger::relative_residual() const {
  const double change = final_energy_j - initial_energy_j;
  const double residual = motor_work_j - (change + structural_dissipation_j + contact_dissipation_j);
  const double scale = std::max({std::abs(motor_work_j), std::abs(change), std::abs(structural_dissipation_j),
                                 std::abs(contact_dissipation_j), std::abs(initial_energy_j), 1e-300});
  return std::abs(residual) / scale;
}

namespace reference_internal {

void Solver::run(const ModalState& initial, double duration) {
  end_time_ = duration;
  double t = 0;
  ModalState x = initial;
  const TipState s0 = tip_state(x.q.data(), x.v.data(), 0, Phase::free);
  solution_.energy.initial_energy_j = mechanical_energy(x.q.data(), x.v.data(), s0.indentation);
  Phase phase = Phase::free;
  bool after_contact = false;
  if (s0.indentation > 0 || (s0.indentation == 0 && s0.indentation_rate > 0)) {
    if (is_instantaneous(model_.contact)) {
      if (s0.indentation > 0)
        return fail(RunStatus::failed, "the Newton law cannot start with the tips interpenetrating (delta = " +
                                           std::to_string(s0.indentation) + " m at t = 0)");
      phase = Phase::sticking;  // touching and closing: treated as an impact below
    } else {
      phase = Phase::compliant;
    }
  }
  if (phase == Phase::sticking) {  // Newton, touching at t = 0
    if (!newton_impact(t, x)) phase = Phase::free, after_contact = true;
  }
  run_phases(t, std::move(x), phase, after_contact);
}

void Solver::run_after_contact(const FlightStart& start, double duration) {
  end_time_ = duration;
  const TipState s0 = tip_state(start.state.q.data(), start.state.v.data(), start.t_s, Phase::free);
  solution_.energy.initial_energy_j = mechanical_energy(start.state.q.data(), start.state.v.data(), s0.indentation);
  run_phases(start.t_s, start.state, Phase::free, true);
}

void Solver::run_phases(double t, ModalState x, Phase phase, bool after_contact) {
  while (t < end_time_) {
    if (solution_.impacts > settings_.max_contact_episodes)
      return fail(RunStatus::failed, "more than " + std::to_string(settings_.max_contact_episodes) +
                                         " contact episodes by t = " + std::to_string(t) + " s: chatter not resolved");
    if (chatter_guard(t)) return;
    switch (phase) {
      case Phase::free: {
        if (after_contact) keep_flight_start(t, x);
        if (!free_flight(t, x, after_contact)) break;  // reached the end
        if (is_instantaneous(model_.contact)) {
          phase = newton_impact(t, x) ? Phase::sticking : Phase::free;
          after_contact = true;
        } else {
          phase = Phase::compliant;
        }
        break;
      }
      case Phase::compliant:
        if (!integrate_contact(t, x, Phase::compliant)) return;
        phase = Phase::free;
        after_contact = true;
        break;
      case Phase::sticking:
        if (!integrate_contact(t, x, Phase::sticking)) return;
        phase = Phase::free;
        after_contact = true;
        break;
    }
  }
  const TipState s = tip_state(x.q.data(), x.v.data(), t, phase == Phase::free ? Phase::free : phase);
  solution_.energy.final_energy_j = mechanical_energy(x.q.data(), x.v.data(), s.indentation);
  solution_.final_state = x;
}

// Only the last start before keep_flight_starts_from_s is kept, and every one after it.
void Solver::keep_flight_start(double t, const ModalState& x) {
  std::vector<FlightStart>& starts = solution_.flight_starts;
  if (settings_.keep_flight_starts_from_s == kInf) return;
  if (t < settings_.keep_flight_starts_from_s) starts.clear();
  starts.push_back({t, x});
}

// Stops a run whose contact episodes pile up without time advancing (a guard; physics never needs it).
bool Solver::chatter_guard(double t) {
  if (solution_.impacts - guard_impacts_ < 100000) return false;
  if (t - guard_time_ < 1e-9) {
    std::ostringstream why;
    why << "100000 contact episodes within " << (t - guard_time_) << " s at t = " << t << " s: chatter not resolved";
    fail(RunStatus::failed, why.str());
    return true;
  }
  guard_impacts_ = solution_.impacts;
  guard_time_ = t;
  return false;
}

}  // namespace reference_internal

using reference_internal::Solver;

namespace {
void check_settings(const ReferenceSettings& settings) {
  if (!(settings.relative_tolerance > 0) || !(settings.absolute_tolerance > 0))
    throw std::invalid_argument("reference tolerances must be > 0");
  if (settings.grid_points_per_period < 4) throw std::invalid_argument("grid_points_per_period must be >= 4");
  if (!(settings.max_grid_step_s > 0)) throw std::invalid_argument("max_grid_step_s must be > 0");
}
}  // namespace

ReferenceSolution solve_reference(const ModalModel& model, const ModalState& initial, double duration_s,
                                  const OutputWindow& output, const ReferenceSettings& settings) {
  check_settings(settings);
  ReferenceSolution solution;
  Solver solver(model, output, settings, solution);
  solver.run(initial, duration_s);
  return solution;
}

ReferenceSolution solve_reference_after_contact(const ModalModel& model, const FlightStart& start, double duration_s,
                                                const OutputWindow& output, const ReferenceSettings& settings) {
  check_settings(settings);
  ReferenceSolution solution;
  Solver solver(model, output, settings, solution);
  solver.run_after_contact(start, duration_s);
  return solution;
}

}  // namespace ib
