// Exact motion of the modal equations between contacts. With no contact force every mode is a linear
// damped oscillator driven by the motor, so the state at any time follows in closed form:
//   x(t0 + tau) = x_p(t0 + tau) + exp(A_m tau) (x(t0) - x_p(t0)),
// x_p the steady-state response to the motor and exp(A_m tau) the 2x2 transition of each mode
// (under-, critically or over-damped alike: the chain's stiffness-proportional damping overdamps its
// fastest modes).
#pragma once

#include <Eigen/Core>

#include "modal_model.h"

namespace ib {

class FreeFlight {
 public:
  explicit FreeFlight(const ModalModel& model);

  // The transition of every mode over a fixed interval tau: q(tau) = qq q0 + qv v0, v(tau) = vq q0 + vv v0.
  struct Transition {
    double tau_s = 0;
    Eigen::ArrayXd qq, qv, vq, vv;
  };
  Transition transition(double tau_s) const;

  // Steady-state response to the motor at time t (zero without a motor).
  void steady_state(double t, ModalState& x) const;

  // x at t0 + T.tau from x0 at t0.
  void advance(const Transition& transition, const ModalState& x0, double t0, ModalState& x) const;
  void advance(const ModalState& x0, double t0, double tau_s, ModalState& x) const {
    advance(transition(tau_s), x0, t0, x);
  }

 private:
  const ModalModel& model_;
  Eigen::ArrayXd decay_;         // -zeta omega [1/s]
  Eigen::ArrayXd oscillation_;   // omega sqrt(|1 - zeta^2|) [rad/s]
  Eigen::ArrayXi regime_;        // -1 under-, 0 critically, +1 over-damped
  Eigen::ArrayXd forced_cos_, forced_sin_;  // q_p = forced_cos cos(Omega t) - forced_sin sin(Omega t)
};

}  // namespace ib
