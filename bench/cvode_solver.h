// The reference's modal equations integrated with SUNDIALS CVODE, its root finding locating contact onset
// and release, as a competent user of CVODE would (bench/cvode_reference.cpp is the command; docs/performance.md,
// "CVODE beside SciPy (issue 30)", the measurements). The same events as bench/scipy_reference.py:
//
// - free flight: the whole run is integrated (the reference propagates it in closed form); the root
//   delta = b . q - gap crossing 0 upward starts a contact;
// - a compliant contact (Hertz, spring-dashpot): integrated with the contact force and its impulse as one
//   more state, until delta crosses 0 downward (CVODE re-initialised at each: the right-hand side jumps
//   there). Inside, roots that need no restart: delta' crossing 0 downward (the largest indentation),
//   d/dt of the law's unclipped expression crossing 0 downward (the largest force) and, for clipped laws,
//   that expression crossing 0 (an episode whose force ended before the overlap did ends there, as in the
//   reference and the SciPy comparator);
// - Newton: the reference's modal impulse map at each onset, q' -= b (1 + e) delta' / (b . b); where the
//   impacts would accumulate (the reference then makes the tips stick) the run stops with a message, as
//   the SciPy comparator does.
//
// Like any root finder on step ends, a contact that starts and ends inside one step would be missed.
#pragma once

#include <string>
#include <vector>

#include "cvode_modal_model.h"

namespace ib::bench {

struct CvodeSettings {
  double rtol = 1e-9;
  double atol = 1e-12;  // [m sqrt(kg)] on every state (and on the impulse, in N s)
  // adams: Adams-Moulton with fixed-point iteration, CVODE's choice for non-stiff problems (no Jacobian);
  // adams-newton: the same with Newton iteration on a dense difference-quotient Jacobian; bdf: BDF with it.
  std::string method = "adams";
};

// One contact episode, the fields of model/trajectory.h's ContactEvent (events.csv).
struct CvodeEvent {
  double onset = 0, end = 0;   // [s]
  double approach = 0;         // delta' at the onset [m/s]
  double rebound = 0;          // -delta' at the end [m/s]
  double restitution = 0;      // rebound / approach [-]
  double peak_force = 0;       // [N]; NaN for Newton
  double impulse = 0;          // [N s]
  double max_indentation = 0;  // [m]
};

// Tip displacement and velocity of both frames at one output sample (only with record_samples).
struct CvodeSample {
  double t = 0, displacement1 = 0, displacement2 = 0, velocity1 = 0, velocity2 = 0;
};

struct CvodeResult {
  bool ok = true;
  std::string reason;  // why the run stopped, when !ok
  std::vector<CvodeEvent> events;
  std::vector<CvodeSample> samples;
  long steps = 0, rhs_evaluations = 0, root_evaluations = 0, nonlinear_iterations = 0, jacobian_evaluations = 0;
  long phases = 0;                         // CVODE (re)initialisations: one per free flight or contact phase
  double cpu_time_s = 0, wall_time_s = 0;  // the integration, events included; reading the model not
};

// Integrates the whole run. With record_samples, also the tip motion at the model's output samples
// (from series_start_s at output_rate_hz), taken from CVODE's interpolant: the steps are not changed by it.
CvodeResult solve_with_cvode(const ModalModel& model, const CvodeSettings& settings, bool record_samples);

// The SUNDIALS version the comparator is linked with, e.g. "6.4.1".
std::string sundials_version();

}  // namespace ib::bench
