#include "bench/contact_phase_steppers.h"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ib::bench {
namespace {

namespace odeint = boost::numeric::odeint;
using VectorState = std::vector<double>;
using UblasState = boost::numeric::ublas::vector<double>;

// The first step, as the reference takes it: never beyond a microsecond, the contact's scale being unknown.
constexpr double kFirstStep_s = 1e-6;

// First root of f on [a, b] given f(a), f(b) of opposite signs, to `bits` bits (the reference's find_root:
// 50 bits for event times, 26 for the location of an extremum, whose value is flat in it), here of the time
// since the onset.
template <class F>
double find_root(F&& f, double a, double b, double fa, double fb, int bits = 50) {
  if (fa == 0) return a;
  if (fb == 0) return b;
  if ((fa > 0) == (fb > 0)) return std::abs(fa) < std::abs(fb) ? a : b;
  std::uintmax_t iterations = 60;
  const auto bracket =
      boost::math::tools::toms748_solve(f, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(bits), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// The cubic Hermite through (0, f0, slope0) and (h, f1, slope1), at s in [0, h], and its derivative.
struct Hermite {
  double h, f0, f1, d0, d1;
  double value(double s) const {
    const double u = s / h, u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * f0 + (u3 - 2 * u2 + u) * h * d0 + (-2 * u3 + 3 * u2) * f1 + (u3 - u2) * h * d1;
  }
  double slope(double s) const {
    const double u = s / h, u2 = u * u;
    return ((6 * u2 - 6 * u) * f0 + (-6 * u2 + 6 * u) * f1) / h + (3 * u2 - 4 * u + 1) * d0 + (3 * u2 - 2 * u) * d1;
  }
};

ContactKinematics kinematics_of(const ContactPhaseSystem& system, const VectorState& y, double t) {
  return system.kinematics(y.data(), t);
}
ContactKinematics kinematics_of(const ContactPhaseSystem& system, const UblasState& y, double t) {
  return system.kinematics(&y[0], t);
}

template <class State>
State start_state(const ContactPhaseSystem& system, const ContactOnset& onset) {
  State y(system.size());
  for (int i = 0; i < system.size(); ++i) y[i] = 0;
  for (int m = 0; m < system.modes(); ++m) y[m] = onset.state.q[m], y[system.modes() + m] = onset.state.v[m];
  return y;
}

template <class State>
ContactOutcome finish(const ContactPhaseSystem& system, double t_end, const State& y_end, double peak_force,
                      long long steps) {
  ContactOutcome out;
  out.duration_s = t_end;  // time runs from the onset (contact_phase_system.h)
  out.rebound_velocity_m_s = -kinematics_of(system, y_end, t_end).indentation_rate;
  out.impulse_n_s = y_end[system.impulse_index()];
  out.peak_force_n = peak_force;
  out.steps = steps;
  return out;
}

// A stepper with dense output, stepped as reference/contact_phase.cpp steps Dormand-Prince. retake(y_prev,
// ta, t_stop, eval) gives the state at t_stop < tb from the step's start (or from the dense output).
template <class State, class Dense, class System, class Retake>
ContactOutcome run_dense(const ContactPhaseSystem& system, Dense& dense, System&& equations, double max_step_s,
                         const ContactOnset& onset, Retake&& retake) {
  State y = start_state<State>(system, onset), ys(system.size()), y_prev(system.size());
  dense.initialize(y, 0.0, std::min(max_step_s, kFirstStep_s));
  ContactKinematics ka = kinematics_of(system, y, 0.0);
  double peak = ka.force;
  long long steps = 0;
  auto eval = [&](double ts) {
    dense.calc_state(ts, ys);
    return kinematics_of(system, ys, ts);
  };
  while (true) {
    y_prev = dense.current_state();
    dense.do_step(equations);
    ++steps;
    const double ta = dense.previous_time(), tb = dense.current_time();
    const State& yb = dense.current_state();
    ContactKinematics kb = kinematics_of(system, yb, tb);
    if (!std::isfinite(kb.indentation)) throw std::runtime_error("non-finite state in a contact phase");
    double t_stop = tb;
    const bool separated = kb.indentation < 0;
    if (separated) {  // separated within the step: after its last interior maximum of delta
      double lo = ta, f_lo = ka.indentation;
      if (f_lo <= 0) {
        lo = find_root([&](double s) { return eval(s).indentation_rate; }, ta, tb, ka.indentation_rate,
                       kb.indentation_rate);
        f_lo = eval(lo).indentation;
      }
      t_stop = f_lo > 0 ? find_root([&](double s) { return eval(s).indentation; }, lo, tb, f_lo, kb.indentation) : lo;
    }
    State y_stop = yb;
    if (t_stop < tb) {
      retake(y_prev, ta, t_stop, y_stop);
      kb = kinematics_of(system, y_stop, t_stop);
    }
    peak = std::max({peak, ka.force, kb.force});
    if (ka.force_rate > 0 && kb.force_rate < 0) {
      const double c =
          find_root([&](double s) { return eval(s).force_rate; }, ta, t_stop, ka.force_rate, kb.force_rate, 26);
      peak = std::max(peak, eval(c).force);
    }
    if (separated) return finish(system, t_stop, y_stop, peak, steps);
    ka = kb;
  }
}

// A controlled-only Runge-Kutta stepper: no dense output, so every point inside a step is a retaken step.
template <class ErrorStepper>
ContactOutcome run_controlled(const ContactPhaseSystem& system, const StepperTolerance& tolerance, double max_step_s,
                              const ContactOnset& onset) {
  auto controlled = odeint::make_controlled(tolerance.absolute, tolerance.relative, max_step_s, ErrorStepper());
  ErrorStepper plain;
  auto equations = [&](const VectorState& s, VectorState& ds, double ts) { system.rhs(s, ds, ts); };
  VectorState y = start_state<VectorState>(system, onset), y_prev(y.size()), ys(y.size());
  double t = 0, dt = std::min(max_step_s, kFirstStep_s);
  ContactKinematics ka = kinematics_of(system, y, t);
  double peak = ka.force;
  long long steps = 0;
  auto retake = [&](double ta, double s) {
    plain.do_step(equations, y_prev, ta, ys, s - ta);
    return kinematics_of(system, ys, s);
  };
  while (true) {
    y_prev = y;
    const double ta = t;
    for (int tries = 0; controlled.try_step(equations, y, t, dt) == odeint::fail; ++tries)
      if (tries > 500) throw std::runtime_error("step size control failed in a contact phase");
    ++steps;
    const double tb = t, h = tb - ta;
    const ContactKinematics kb = kinematics_of(system, y, tb);
    if (!std::isfinite(kb.indentation)) throw std::runtime_error("non-finite state in a contact phase");
    peak = std::max({peak, ka.force, kb.force});
    if (ka.force_rate > 0 && kb.force_rate < 0) {  // a force maximum inside: its value from one retaken step
      const Hermite force{h, ka.force, kb.force, ka.force_rate, kb.force_rate};
      const double c = find_root([&](double s) { return force.slope(s); }, 0, h, ka.force_rate, kb.force_rate, 26);
      // The cubic's maximum is off the true one by O(h^4): F there is short of the peak by F'^2 / (2 |F''|), a
      // correction the retaken step's F' gives at no further cost (F'' from the step's ends).
      const ContactKinematics kc = retake(ta, ta + c);
      const double curvature = (kb.force_rate - ka.force_rate) / h;
      peak = std::max(peak, kc.force - kc.force_rate * kc.force_rate / (2 * curvature));
    }
    if (kb.indentation < 0) {
      if (!(ka.indentation > 0)) throw std::runtime_error("a contact phase ended within one step of its onset");
      const Hermite gap{h, ka.indentation, kb.indentation, ka.indentation_rate, kb.indentation_rate};
      double s = ta + find_root([&](double u) { return gap.value(u); }, 0, h, ka.indentation, kb.indentation);
      ContactKinematics ks = retake(ta, s);
      for (int i = 0; i < 20; ++i) {  // Newton: delta' of the retaken step is exact to the step's accuracy
        const double correction = ks.indentation / ks.indentation_rate;
        s = std::clamp(s - correction, ta, tb);
        ks = retake(ta, s);
        // converging quadratically: after a correction this small the next one would be below rounding
        if (std::abs(correction) <= 1e-7 * h) break;
      }
      return finish(system, s, ys, peak, steps);
    }
    ka = kb;
  }
}

}  // namespace

const char* to_string(ContactStepper stepper) {
  switch (stepper) {
    case ContactStepper::dopri5:
      return "dopri5";
    case ContactStepper::cash_karp54:
      return "cash_karp54";
    case ContactStepper::fehlberg78:
      return "fehlberg78";
    case ContactStepper::bulirsch_stoer:
      return "bulirsch_stoer";
    case ContactStepper::rosenbrock4:
      return "rosenbrock4";
  }
  return "?";
}

ContactStepper contact_stepper_from_string(const std::string& name) {
  for (ContactStepper s : {ContactStepper::dopri5, ContactStepper::cash_karp54, ContactStepper::fehlberg78,
                           ContactStepper::bulirsch_stoer, ContactStepper::rosenbrock4})
    if (name == to_string(s)) return s;
  throw std::invalid_argument("unknown stepper '" + name +
                              "'; allowed: dopri5, cash_karp54, fehlberg78, bulirsch_stoer, rosenbrock4");
}

ContactOutcome integrate_contact_phase(const ContactPhaseSystem& system, ContactStepper stepper,
                                       const StepperTolerance& tolerance, double max_step_s,
                                       const ContactOnset& onset) {
  const long long rhs_before = system.rhs_calls, jacobian_before = system.jacobian_calls;
  system.time_origin_s = onset.t_s;
  auto vector_ode = [&](const VectorState& s, VectorState& ds, double ts) { system.rhs(s, ds, ts); };
  ContactOutcome out;
  switch (stepper) {
    case ContactStepper::dopri5: {
      using Dopri = odeint::runge_kutta_dopri5<VectorState>;
      auto dense = odeint::make_dense_output(tolerance.absolute, tolerance.relative, max_step_s, Dopri());
      out = run_dense<VectorState>(system, dense, vector_ode, max_step_s, onset,
                                   [&](const VectorState& y0, double ta, double ts, VectorState& y) {
                                     Dopri().do_step(vector_ode, y0, ta, y, ts - ta);
                                   });
      break;
    }
    case ContactStepper::bulirsch_stoer: {
      // control_interpolation: the dense output's own error is controlled too, as the end state is read from it
      odeint::bulirsch_stoer_dense_out<VectorState> dense(tolerance.absolute, tolerance.relative, 1.0, 1.0, max_step_s,
                                                          true);
      out = run_dense<VectorState>(
          system, dense, vector_ode, max_step_s, onset,
          [&](const VectorState&, double, double ts, VectorState& y) { dense.calc_state(ts, y); });
      break;
    }
    case ContactStepper::rosenbrock4: {
      auto rhs = [&](const UblasState& s, UblasState& ds, double ts) { system.rhs(s, ds, ts); };
      auto jacobian = [&](const UblasState& s, boost::numeric::ublas::matrix<double>& J, double ts, UblasState& dfdt) {
        system.jacobian(s, J, ts, dfdt);
      };
      auto equations = std::make_pair(rhs, jacobian);
      auto dense =
          odeint::make_dense_output(tolerance.absolute, tolerance.relative, max_step_s, odeint::rosenbrock4<double>());
      out = run_dense<UblasState>(system, dense, equations, max_step_s, onset,
                                  [&](const UblasState& y0, double ta, double ts, UblasState& y) {
                                    odeint::rosenbrock4<double>().do_step(equations, y0, ta, y, ts - ta);
                                  });
      break;
    }
    case ContactStepper::cash_karp54:
      out = run_controlled<odeint::runge_kutta_cash_karp54<VectorState>>(system, tolerance, max_step_s, onset);
      break;
    case ContactStepper::fehlberg78:
      out = run_controlled<odeint::runge_kutta_fehlberg78<VectorState>>(system, tolerance, max_step_s, onset);
      break;
  }
  out.rhs_calls = system.rhs_calls - rhs_before;
  out.jacobian_calls = system.jacobian_calls - jacobian_before;
  return out;
}

}  // namespace ib::bench
