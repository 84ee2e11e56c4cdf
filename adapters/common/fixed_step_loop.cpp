#include "adapters/common/fixed_step_loop.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "adapters/common/injected_contact.h"
#include "adapters/common/step_recorder.h"
#include "model/run_clock.h"

namespace ib {

namespace {

// A step's time to 9 digits: a step of 1.5625e-05 s needs more than the stream's 6.
std::string time_text(double t_s) {
  std::ostringstream text;
  text.precision(9);
  text << t_s;
  return text.str();
}

// Why a state ends the run, or nothing: a tip that is not finite, or one beyond the bound. Runs every
// step: the message is written only when there is something to say.
std::optional<std::string> non_finite(const TipState& tips, double t_s) {
  for (int f = 0; f < 2; ++f)
    if (!std::isfinite(tips.displacement_m[f]) || !std::isfinite(tips.velocity_m_s[f])) {
      std::ostringstream why;
      why << "non-finite state of frame " << f + 1 << " at t = " << time_text(t_s)
          << " s (tip u = " << tips.displacement_m[f] << " m, v = " << tips.velocity_m_s[f] << " m/s)";
      return why.str();
    }
  return std::nullopt;
}

std::optional<std::string> beyond_bound(const TipState& tips, const RigSpec& rig, const StabilityBounds& bounds,
                                        double t_s) {
  for (int f = 0; f < 2; ++f) {
    const double bound_m = bounds.displacement_bound_fraction_of_length * rig.frames[f].tip_z_m;
    if (std::abs(tips.displacement_m[f]) > bound_m) {
      std::ostringstream why;
      why << "frame " << f + 1 << " tip displacement |u| = " << std::abs(tips.displacement_m[f]) << " m beyond "
          << bounds.displacement_bound_fraction_of_length << " L = " << bound_m << " m at t = " << time_text(t_s)
          << " s";
      return why.str();
    }
  }
  return std::nullopt;
}

}  // namespace

double resolve_time_step_s(const RunSettings& settings, double default_step_s, const std::string& engine) {
  if (!(settings.time_step_s >= 0) || !std::isfinite(settings.time_step_s))
    throw std::invalid_argument(engine + ": the time step must be > 0 (or 0 for the default " +
                                std::to_string(default_step_s) + " s), got " + std::to_string(settings.time_step_s));
  return settings.time_step_s > 0 ? settings.time_step_s : default_step_s;
}

std::optional<std::string> nonfinite_hinges(double t_s, const TipState& tips,
                                            const std::array<Eigen::VectorXd, 2>& angles,
                                            const std::array<Eigen::VectorXd, 2>& rates) {
  const bool tips_finite =
      std::isfinite(tips.displacement_m[0] + tips.displacement_m[1] + tips.velocity_m_s[0] + tips.velocity_m_s[1]);
  if (!tips_finite || (angles[0].allFinite() && angles[1].allFinite() && rates[0].allFinite() && rates[1].allFinite()))
    return std::nullopt;
  std::ostringstream why;
  why << "non-finite hinge angle or rate at t = " << t_s << " s";
  return why.str();
}

void run_fixed_steps(FixedStepEngine& engine, const RigSpec& rig, const Scenario& scenario, const RunSettings& settings,
                     RunResult& result) {
  const double step_s = engine.time_step_s();
  result.time_step_s = step_s;
  const long long steps = static_cast<long long>(std::ceil(scenario.duration_s / step_s - 1e-9));
  StepRecorder recorder(series_start_s(settings, scenario), scenario.duration_s, settings.output_rate_hz);
  std::optional<InjectedContact> injected;
  if (engine.injects_contact()) injected.emplace(rig);
  auto stop = [&](const std::string& reason) {
    result.status = RunStatus::unstable;
    result.reason = reason;
  };
  if (settings.initial_state) engine.restore_state(*settings.initial_state);
  // the chains' modal damping matrices, when they have one: the loop applies -C theta' (held over a step)
  const bool modal_damping = rig.frames[0].chain.modal_damping_n_m_s_per_rad.size() > 0 ||
                             rig.frames[1].chain.modal_damping_n_m_s_per_rad.size() > 0;
  std::array<Eigen::VectorXd, 2> hinge_rates_rad_s = zero_hinge_values(rig), damping_torques_n_m = hinge_rates_rad_s;
  const RunClock clock;
  double contact_force_n = 0;  // during the step that ends at the state read next
  for (long long n = 0;; ++n) {
    const double t = static_cast<double>(n) * step_s;
    TipState tips;
    if (auto trouble = engine.read_tips(t, tips)) {
      stop(*trouble);
      break;
    }
    if (auto why = non_finite(tips, t)) {
      stop(*why + engine.explain_instability());
      break;
    }
    StepState state;
    state.t = t;
    state.displacement_m = tips.displacement_m;
    state.velocity_m_s = tips.velocity_m_s;
    state.contact_force_n = contact_force_n;
    state.indentation_m = tips.displacement_m[0] - tips.displacement_m[1] - rig.gap_m;
    state.energy_j = recorder.energy_where_needed(t, step_s, [&] { return engine.energy_j(state.indentation_m); });
    recorder.record(state);
    if (auto why = beyond_bound(tips, rig, settings.stability, t)) {
      stop(*why + engine.explain_instability());
      break;
    }
    if (n == steps) break;

    StepLoads loads;
    loads.t_s = t;
    if (rig.motor) loads.motor_force_n = rig.motor->at(t);
    if (injected)
      loads.injected_contact_force_n = injected->force(tips.displacement_m[0], tips.velocity_m_s[0],
                                                       tips.displacement_m[1], tips.velocity_m_s[1], step_s);
    if (modal_damping && engine.read_hinge_rates(hinge_rates_rad_s)) {
      for (int f = 0; f < 2; ++f) {
        const Eigen::MatrixXd& c = rig.frames[f].chain.modal_damping_n_m_s_per_rad;
        if (c.size() > 0) damping_torques_n_m[f].noalias() = -c * hinge_rates_rad_s[f];
      }
      loads.hinge_damping_torques_n_m = &damping_torques_n_m;
    }
    engine.apply_loads(loads);
    if (auto trouble = engine.step()) {
      stop(*trouble);
      break;
    }
    // a tensile law force (the unclipped spring-dashpot near separation) is applied and recorded as it is
    contact_force_n = injected ? *loads.injected_contact_force_n : engine.contact_force_n();
  }
  clock.stop_into(result.cost);
  if (result.status == RunStatus::ok) result.final_state = engine.save_state();
  result.cost.steps = recorder.steps();
  result.trajectory = recorder.finish();
  result.impact_zoom = recorder.impact_zoom();
}

}  // namespace ib
