// The one mapping from a physical spring-damper to ODE's constraint softness, used for the hinge
// springs (joint stops) and for the spring-dashpot contact alike.
//
// ODE solves each constraint row as  J v_{n+1} + CFM f = (ERP / h) e_n  with f the row's force and
// e_n the constraint error at the start of the step. With
//     ERP = h k / (h k + c),   CFM = 1 / (h k + c)
// that row gives f = k (e_n + h e'_{n+1}) + c e'_{n+1} = k e_{n+1} + c e'_{n+1}: the spring and the
// damper evaluated at the end of the step, i.e. the implicit (backward) Euler spring-dashpot. It is
// stable at any step but damps: a mode of frequency omega gets an extra damping ratio of about
// omega h / 2 (ODE's user guide, "How to use ERP and CFM"; engines.md).
#pragma once

namespace ib::ode {

struct SoftConstraint {
  double erp = 0;  // error reduction parameter [-], in (0, 1]
  double cfm = 0;  // constraint force mixing [m/(N s)] for a linear row, [rad/(N m s)] for an angular one
};

// stiffness k [N/m or N m/rad] >= 0, damping c [N s/m or N m s/rad] >= 0, not both zero; step h [s] > 0.
// Throws std::invalid_argument otherwise.
SoftConstraint soft_constraint(double stiffness, double damping, double time_step_s);

}  // namespace ib::ode
