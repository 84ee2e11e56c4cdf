// The reference's modal model as `impactbench export SCENARIO --engine reference` writes it (JSON), read for
// the CVODE comparator (bench/cvode_reference.cpp), as bench/scipy_modal_model.py reads it for SciPy:
//
//   q'' + 2 zeta omega q' + omega^2 q = p F_m(t) - b F_c,   delta = b . q - gap,   F_m = A cos(Omega t),
//
// modal coordinates in m sqrt(kg), SI units everywhere else. Only bench/ uses it: the comparator reads the
// file, never the reference's own structures, so that it integrates what any outside solver would be given.
#pragma once

#include <string>
#include <vector>

namespace ib::bench {

// F_c(delta, delta') of one law (rig.md section 3), continued smoothly to delta < 0 as the reference does
// inside a contact phase: the phase ends where delta returns to 0, so the continuation only keeps the
// right-hand side smooth across the step that crosses the separation.
struct ContactLaw {
  enum class Kind { hertz, viscoelastic, newton };
  Kind kind = Kind::hertz;
  std::string name;
  double stiffness = 0;    // Hertz: k [N/m^n]; viscoelastic: k [N/m]
  double exponent = 1;     // Hertz: n [-]
  double damping = 0;      // Hertz: c [N s/m^(n+1)]; viscoelastic: c [N s/m]
  double restitution = 0;  // Newton: e [-]
  bool clipped = false;    // the force is clipped at zero (Hertz always; viscoelastic when clip_tension)

  bool instantaneous() const { return kind == Kind::newton; }
  // The law's expression before clipping [N]: its sign changes where a clipped force ends or returns.
  double unclipped(double delta, double rate) const;
  // Contact force inside a contact phase [N].
  double force(double delta, double rate) const;
  // d/dt of the unclipped expression [N/s] along a motion with delta, delta', delta'': zero at a force
  // maximum (and smooth where the clipped force is flat zero, so a root search on it sees no plateau).
  double unclipped_rate(double delta, double rate, double acceleration) const;
};

struct ModalModel {
  std::string path, scenario;
  std::vector<double> omega, zeta;   // [rad/s], [-]
  std::vector<double> b, p;          // contact and motor levers [1/sqrt(kg)]
  std::vector<double> tip1, tip2;    // each frame's recorded tip lever [1/sqrt(kg)]
  std::vector<double> q0, v0;        // initial state [m sqrt(kg)], [m/s sqrt(kg)]
  std::vector<double> damping_rate;  // 2 zeta omega [1/s]
  std::vector<double> stiffness;     // omega^2 [1/s^2]
  double gap = 0;                    // [m]
  double motor_amplitude = 0;        // [N]
  double motor_omega = 0;            // [rad/s]
  ContactLaw law;
  double duration = 0;           // [s]
  double series_start = 0;       // first output sample [s]
  double output_rate = 0;        // [Hz]
  double rtol = 0, atol = 0;     // the reference's tolerances [-], [m sqrt(kg)]
  double accumulation_time = 0;  // Newton: the reference sticks when impacts accumulate within this [s]
  double lever_norm2 = 0;        // b . b = 1 / effective mass of the relative tip motion [1/kg]

  std::size_t modes() const { return omega.size(); }
  double motor(double t) const;  // F_m(t) [N]
};

// Reads and checks the file; throws std::runtime_error naming the file, the key, the value and what is allowed.
ModalModel read_modal_model(const std::string& path);

}  // namespace ib::bench
