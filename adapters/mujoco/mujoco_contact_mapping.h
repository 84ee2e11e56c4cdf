// From physical contact parameters to MuJoCo's solref/solimp, in one tested place.
//
// MuJoCo 2.2.2 computes a contact's normal force from a reference acceleration
//   aref = -b v - k imp r            (r: signed distance, < 0 in penetration; v: its rate)
// and an impedance imp (solimp) that sets how much of aref the solver enforces. With a negative
// ("direct") solref = (-K, -B): k = K / dmax^2 and b = B / dmax. With imp constant and tiny
// (dmin = dmax = d = 1e-4, the smallest MuJoCo allows) the regulariser R = (1 - d)/d A dominates the
// contact's true inverse inertia, and the force becomes
//   f = (K delta + B delta') / ((1 - d) A) - small terms of relative size d,
// with delta = -r the indentation and A = body_invweight0 (translation) of the two bodies summed:
// MuJoCo's own frozen estimate of the contact's inverse mass (efc_diagApprox), not the true one.
// So a spring-dashpot k [N/m], c [N s/m] is K = k A (1 - d), B = c A (1 - d) (engines.md).
// The solver never pulls: the force is the spring-dashpot clipped at zero.
#pragma once

#include <array>

namespace ib {

struct SolrefSolimp {
  std::array<double, 2> solref{};  // negative: (-K [1/s^2], -B [1/s]), per unit of inverse mass
  std::array<double, 5> solimp{};  // (dmin, dmax, width [m], midpoint, power)
};

// The impedance used by the direct mapping: constant, at MuJoCo's lower clamp.
constexpr double kDirectImpedance = 1e-4;

// solref/solimp for a linear spring-dashpot of stiffness k [N/m] and damping c [N s/m] between two
// bodies whose body_invweight0 translational terms sum to invweight_sum [1/kg].
SolrefSolimp map_spring_dashpot(double stiffness_n_per_m, double damping_n_s_per_m, double invweight_sum_per_kg);

// The spring-dashpot it implies, back from solref (the inverse of map_spring_dashpot).
struct SpringDashpot {
  double stiffness_n_per_m = 0;
  double damping_n_s_per_m = 0;
};
SpringDashpot spring_dashpot_of(const SolrefSolimp& parameters, double invweight_sum_per_kg);

// A spring-dashpot that cannot pull (MuJoCo's contact), between two free bodies of reduced mass m,
// hit at speed v0: m x'' + c x' + k x = 0 while k x + c x' > 0. Closed forms in the damping ratio
// zeta = c / (2 sqrt(k m)) < 1/sqrt(2): the force ends before the overlap does, at the phase
//   phi = omega_d t_end = pi - atan2(2 zeta sqrt(1 - zeta^2), 1 - 2 zeta^2),
// and the tips leave with v0 e, e = exp(-zeta phi / sqrt(1 - zeta^2)) (zeta sin(phi) / sqrt(1 - zeta^2) - cos(phi)).
double clipped_contact_phase(double damping_ratio);        // phi [rad]
double clipped_contact_restitution(double damping_ratio);  // e [-]

// The contact MuJoCo uses for Newton's law (it has no restitution): the no-tension spring-dashpot on
// the tips' effective mass [kg] whose rebound is e and whose force lasts duration_s [s].
// e must be reachable by an underdamped contact that cannot pull: 0.2103 (zeta = 0.7) < e <= 1.
SpringDashpot spring_dashpot_for_restitution(double restitution, double effective_mass_kg, double duration_s);

}  // namespace ib
