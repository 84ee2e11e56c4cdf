// The scenario model: the physical rig, its excitation, its initial state and its contact laws,
// exactly as a scenario file states them (rig.md sections 1-3, 7). Plain data, SI units throughout.
// Numerical settings (time step, tolerances, mode counts) are not part of a scenario: see RunSettings.
#pragma once

#include <array>
#include <optional>
#include <string>

namespace ib {

// One frame: its columns act together as one clamped-free Euler-Bernoulli beam with a tip mass.
struct FrameSpec {
  int columns = 2;                      // columns per frame [-]
  double youngs_modulus_pa = 200e9;     // E [Pa]
  double density_kg_m3 = 7850;          // rho [kg/m^3]
  double column_thickness_m = 1.75e-3;  // h [m], bending direction
  double column_width_m = 76.2e-3;      // b [m]
  double length_m = 0.300;              // L [m]
  double tip_mass_kg = 0.41380;         // M_t [kg]: top plate (+ motor and unbalance on frame 1)
  double damping_ratio = 0.003;         // zeta [-], every mode

  double bending_stiffness_n_m2() const;  // EI = columns E b h^3 / 12 [N m^2]
  double mass_per_length_kg_m() const;    // rho A = columns rho b h [kg/m]
  double beam_mass_kg() const { return mass_per_length_kg_m() * length_m; }
};

// The unbalanced motor on frame 1's tip: F_m(t) = m_u e_u Omega^2 cos(Omega t).
struct MotorSpec {
  double unbalance_mass_kg = 6.59e-3;  // m_u [kg]
  double unbalance_radius_m = 15e-3;   // e_u [m]
  // The speed is given either as a ratio of frame 1's first natural frequency (continuous beam with
  // its tip mass) or directly in Hz; exactly one is set. motor_frequency_hz() resolves it.
  std::optional<double> speed_ratio_to_f1;  // [-]
  std::optional<double> frequency_hz;       // [Hz]
};

// Hertz with hysteresis damping: F = k delta^n (1 + c/k delta'), zero where negative (rig.md 3.1).
struct HertzSpec {
  double stiffness = 2.31e10;             // k_h [N/m^n]
  double exponent = 1.5;                  // n [-]
  double restitution = 0.8;               // e [-], calibrates c_h
  double approach_velocity_m_s = 0.1644;  // v_rel [m/s], calibrates c_h
  std::optional<double> damping;          // explicit c_h [N s/m^(n+1)]; default from the formula

  // c_h = 3 k_h (1 - e^2) / (4 v_rel) unless given explicitly [N s/m^(n+1)]
  double damping_coefficient() const;
};

// Kelvin-Voigt spring-dashpot: F = k delta + c delta' (rig.md 3.2).
struct ViscoelasticSpec {
  double stiffness_n_per_m = 6.99e6;  // k_v [N/m]
  double damping_n_s_per_m = 170.07;  // c_v [N s/m]
  bool clip_tension = false;          // clip F at zero (the published law is not clipped)
};

// Newton's coefficient of restitution, instantaneous impact (rig.md 3.3).
struct NewtonSpec {
  double restitution = 0.8;  // e [-]
};

enum class ContactLaw { hertz, viscoelastic, newton };
const char* to_string(ContactLaw law);
std::optional<ContactLaw> contact_law_from_string(const std::string& name);

// The laws a scenario defines parameters for; a run picks one of them.
struct ContactSpec {
  std::optional<HertzSpec> hertz;
  std::optional<ViscoelasticSpec> viscoelastic;
  std::optional<NewtonSpec> newton;
  bool has(ContactLaw law) const;
};

// Initial state. Frame 1 may start deflected in its static tip-load shape (the shape under a static
// force at its tip) with the given tip displacement, released from rest; everything else starts at rest.
struct InitialSpec {
  double frame1_tip_displacement_m = 0;  // [m], positive toward frame 2
};

struct Scenario {
  std::string name;         // short identifier, e.g. "resonance"
  std::string description;  // what the scenario is and what it probes
  std::string source_path;  // file it was read from ("" when built in code)

  std::array<FrameSpec, 2> frames;  // frames[0] is frame 1 (carries the motor), frames[1] frame 2
  double gap_m = 1e-3;              // d [m]: surface gap between the tips at rest
  std::optional<MotorSpec> motor;   // absent: no motor force (free vibration)
  InitialSpec initial;
  ContactSpec contact;

  double duration_s = 100;       // simulated time [s]
  double scoring_window_s = 14;  // metrics use the last scoring_window_s of the run [s] (scoring_window())
};

// The default rig of rig.md section 1 with the resonance excitation; used by tests and as a template.
Scenario default_rig();

// A run of at most duration_s (--duration of run and suite, a study's duration_s): a longer scenario is cut
// to it, its scoring window, the last part of the run, kept (shortened to the run when longer). Returns
// whether it was cut. The one place of this rule.
bool cut_run(Scenario& scenario, double duration_s);

// Where a run's metrics are taken: [start_s, end_s] of its simulated time [s].
struct ScoringWindow {
  double start_s = 0;
  double end_s = 0;
};

// The one rule of the scoring window: the last `window_s` of the run (a --window, a sweep row's whole motor
// periods; none: the scenario's scoring_window_s), ending at the run's end (duration_s, after cut_run) and
// starting no earlier than t = 0. Every window the program uses, records or writes is this function's.
ScoringWindow scoring_window(const Scenario& scenario, std::optional<double> window_s = std::nullopt);

}  // namespace ib
