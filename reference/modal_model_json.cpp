#include "reference/modal_model_json.h"

#include <nlohmann/json.hpp>
#include <vector>

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// Only the chosen law, its formula in words beside its parameters.
Json law_json(const ContactModel& contact) {
  Json law;
  if (const auto* h = std::get_if<HertzLaw>(&contact)) {
    law["name"] = "hertz";
    law["force"] = "F_c = k delta^n (1 + c/k delta') for delta > 0, zero where that is negative";
    law["stiffness_n_per_m_pow_n"] = h->stiffness;
    law["exponent"] = h->exponent;
    law["damping_n_s_per_m_pow_n_plus_1"] = h->damping;
  } else if (const auto* v = std::get_if<ViscoelasticLaw>(&contact)) {
    law["name"] = "viscoelastic";
    law["force"] = v->clip_tension ? "F_c = k delta + c delta' for delta > 0, zero where that is negative"
                                   : "F_c = k delta + c delta' for delta > 0 (may turn tensile near separation)";
    law["stiffness_n_per_m"] = v->stiffness_n_per_m;
    law["damping_n_s_per_m"] = v->damping_n_s_per_m;
    law["clip_tension"] = v->clip_tension;
  } else {
    law["name"] = "newton";
    law["force"] = "instantaneous: at delta = 0 with delta' > 0, q' -= b (1 + e) delta' / (b . b)";
    law["restitution"] = std::get<NewtonLaw>(contact).restitution;
  }
  return law;
}

// The stacked lever that turns q into frame f's tip displacement: its tip values, zero on the other frame.
Eigen::VectorXd tip_lever(const ModalModel& model, int frame) {
  Eigen::VectorXd lever = Eigen::VectorXd::Zero(model.mode_count());
  const int first = frame == 0 ? 0 : model.frame_mode_count(0);
  lever.segment(first, model.frame_mode_count(frame)) = model.frames[frame].tip;
  return lever;
}

}  // namespace

std::string modal_model_json(const ModalModel& model, const ModalState& initial, const ModelRunInfo& run,
                             const ReferenceSettings& settings) {
  Json j;
  j["format"] = "impactbench modal model 1";
  j["equations"] =
      "q_m'' + 2 zeta_m omega_m q_m' + omega_m^2 q_m = p_m F_m(t) - b_m F_c; delta = b . q - gap_m; "
      "F_m(t) = motor.amplitude_n cos(motor.omega_rad_s t); modal coordinates q in m sqrt(kg)";
  j["scenario"] = run.scenario_name;
  j["scenario_file"] = run.scenario_file;
  j["mode_set"] = model.frames[0].origin;
  j["frame_mode_counts"] = {model.frame_mode_count(0), model.frame_mode_count(1)};
  j["omega_rad_s"] = values(model.omega_rad_s);
  j["zeta"] = values(model.zeta);
  j["contact_lever_per_sqrt_kg"] = values(model.contact_lever);
  j["motor_lever_per_sqrt_kg"] = values(model.motor_lever);
  if (model.motor) j["motor"] = {{"amplitude_n", model.motor->amplitude_n}, {"omega_rad_s", model.motor->omega_rad_s}};
  j["gap_m"] = model.gap_m;
  j["contact_law"] = law_json(model.contact);
  j["initial"] = {{"q_m_sqrt_kg", values(initial.q)}, {"v_m_s_sqrt_kg", values(initial.v)}};
  j["recorded"] = {
      {"meaning",
       "frame f's tip displacement [m], velocity [m/s], acceleration [m/s^2] = lever . q, q', q''; "
       "mechanical energy [J] = sum (q'^2 + omega^2 q^2) / 2 + the law's elastic contact energy in contact"},
      {"frame1_tip_lever_per_sqrt_kg", values(tip_lever(model, 0))},
      {"frame2_tip_lever_per_sqrt_kg", values(tip_lever(model, 1))}};
  j["duration_s"] = run.duration_s;
  j["series_start_s"] = run.series_start_s;
  j["output_rate_hz"] = run.output_rate_hz;
  j["scoring_window_start_s"] = run.scoring_window.start_s;
  j["scoring_window_end_s"] = run.scoring_window.end_s;
  j["reference_settings"] = {{"rtol", settings.relative_tolerance},
                             {"atol_m_sqrt_kg", settings.absolute_tolerance},
                             {"accumulation_time_s", settings.accumulation_time_s}};
  return j.dump(2) + "\n";
}

}  // namespace ib
