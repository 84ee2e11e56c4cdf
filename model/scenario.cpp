// Out-of-line members of the scenario model (scenario.h): derived section properties, the names of the
// contact laws, and the default rig of rig.md section 1.
#include "model/scenario.h"

#include <algorithm>

namespace ib {

// EI = columns E b h^3 / 12: the columns bend together about their thin direction h.
double FrameSpec::bending_stiffness_n_m2() const {
  const double h = column_thickness_m;
  return columns * youngs_modulus_pa * column_width_m * h * h * h / 12.0;
}

// rho A = columns rho b h
double FrameSpec::mass_per_length_kg_m() const { return columns * density_kg_m3 * column_width_m * column_thickness_m; }

// c_h = 3 k_h (1 - e^2) / (4 v_rel) (Lankarani-Nikravesh, rig.md 3.1), unless given explicitly.
double HertzSpec::damping_coefficient() const {
  if (damping) return *damping;
  return 3.0 * stiffness * (1.0 - restitution * restitution) / (4.0 * approach_velocity_m_s);
}

const char* to_string(ContactLaw law) {
  switch (law) {
    case ContactLaw::hertz:
      return "hertz";
    case ContactLaw::viscoelastic:
      return "viscoelastic";
    case ContactLaw::newton:
      return "newton";
  }
  return "unknown";
}

std::optional<ContactLaw> contact_law_from_string(const std::string& name) {
  // One name per law in files, flags and job ids; the linear law is also known by its physics' name.
  if (name == "spring-dashpot" || name == "spring_dashpot") return ContactLaw::viscoelastic;
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
    if (name == to_string(law)) return law;
  }
  return std::nullopt;
}

bool ContactSpec::has(ContactLaw law) const {
  switch (law) {
    case ContactLaw::hertz:
      return hertz.has_value();
    case ContactLaw::viscoelastic:
      return viscoelastic.has_value();
    case ContactLaw::newton:
      return newton.has_value();
  }
  return false;
}

bool cut_run(Scenario& scenario, double duration_s) {
  if (!(duration_s > 0) || scenario.duration_s <= duration_s) return false;
  scenario.duration_s = duration_s;
  scenario.scoring_window_s = std::min(scenario.scoring_window_s, scenario.duration_s);
  return true;
}

ScoringWindow scoring_window(const Scenario& scenario, std::optional<double> window_s) {
  const double length_s = window_s.value_or(scenario.scoring_window_s);
  return {std::max(0.0, scenario.duration_s - length_s), scenario.duration_s};
}

// The values of scenarios/paper/resonance.toml (rig.md sections 1 and 7).
Scenario default_rig() {
  Scenario s;
  s.name = "resonance";
  s.description = "Motor at 1.00 f_1 of frame 1: the published resonance case.";
  s.source_path = "";

  FrameSpec frame;  // two A-36 steel columns, E = 200 GPa, 1.75 x 76.2 mm, L = 0.300 m
  frame.columns = 2;
  frame.youngs_modulus_pa = 200e9;
  frame.density_kg_m3 = 7850.0;
  frame.column_thickness_m = 1.75e-3;
  frame.column_width_m = 76.2e-3;
  frame.length_m = 0.300;
  frame.damping_ratio = 0.003;

  s.frames[0] = frame;
  s.frames[0].tip_mass_kg = 0.64439;  // plate 0.41380 + motor 0.224 + unbalance 0.00659
  s.frames[1] = frame;
  s.frames[1].tip_mass_kg = 0.41380;  // plate only

  s.gap_m = 1.0e-3;

  MotorSpec motor;
  motor.unbalance_mass_kg = 6.59e-3;
  motor.unbalance_radius_m = 15.0e-3;
  motor.speed_ratio_to_f1 = 1.0;
  s.motor = motor;

  s.initial.frame1_tip_displacement_m = 0.0;

  HertzSpec hertz;
  hertz.stiffness = 2.31e10;
  hertz.exponent = 1.5;
  hertz.restitution = 0.8;
  hertz.approach_velocity_m_s = 0.1644;
  s.contact.hertz = hertz;

  ViscoelasticSpec viscoelastic;
  viscoelastic.stiffness_n_per_m = 6.99e6;
  viscoelastic.damping_n_s_per_m = 170.07;
  viscoelastic.clip_tension = false;
  s.contact.viscoelastic = viscoelastic;

  NewtonSpec newton;
  newton.restitution = 0.8;
  s.contact.newton = newton;

  s.duration_s = 100.0;
  s.scoring_window_s = 14.0;
  return s;
}

}  // namespace ib
