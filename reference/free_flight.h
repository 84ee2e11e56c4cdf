// Exact motion of the modal equations between contacts. With no contact force every mode is a linear
// damped oscillator driven by the motor, so the state at any time follows in closed form:
//   x(t0 + tau) = x_p(t0 + tau) + exp(A_m tau) (x(t0) - x_p(t0)),
// x_p the steady-state response to the motor and exp(A_m tau) the 2x2 transition of each mode
// (under-, critically or over-damped alike: the chain's stiffness-proportional damping overdamps its
// fastest modes).
#pragma once

#include <Eigen/Core>

#include "physics/modal_model.h"

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

  // The motor's phase at a time: cos and sin of Omega t (1 and 0 without a motor). Computed once
  // per time and handed on, since the trigonometry dominates the cost of a step.
  struct MotorPhase {
    double t_s = 0, cos = 1, sin = 0;
  };
  MotorPhase motor_phase(double t_s) const;

  // The free part of a state, x - x_p at the motor's phase: what a transition alone carries forward, so that a
  // scan over equal steps needs no trigonometry per step (the steady state is one sinusoid for every mode).
  void free_part(const ModalState& x, const MotorPhase& phase, Eigen::ArrayXd& q_free, Eigen::ArrayXd& v_free) const;
  // The state from its free part and the steady state at the phase.
  void with_steady_state(const Eigen::ArrayXd& q_free, const Eigen::ArrayXd& v_free, const MotorPhase& phase,
                         ModalState& x) const;

  struct EnergyForms;
  // x at to.t_s = from.t_s + transition.tau_s from x0 at from.t_s (x may not be x0). With forms
  // (made for the same tau), also adds the motor work and structural dissipation over the step [J].
  void advance(const Transition& transition, const MotorPhase& from, const MotorPhase& to, const ModalState& x0,
               ModalState& x, const EnergyForms* forms = nullptr, double* motor_work_j = nullptr,
               double* structural_dissipation_j = nullptr) const;
  // The same over any tau (its transition formed in a scratch kept by this object: not for concurrent use).
  void advance(const ModalState& x0, double t0, double tau_s, ModalState& x) const {
    transition_into(tau_s, scratch_);
    advance(scratch_, motor_phase(t0), motor_phase(t0 + tau_s), x0, x);
  }

  // Exact energy integrals over a fixed interval [t0, t0 + tau] as forms in the state at t0,
  // precomputed once per interval length by high-order quadrature of the transition:
  //   integral v_m^2 dt and integral F_m(t) v_m dt, for the structural dissipation
  //   sum 2 zeta omega integral v^2 and the motor work integral F_m(t) u1'(t).
  struct EnergyForms {
    double tau_s = 0;
    Eigen::ArrayXd vv_qq, vv_qv, vv_vv;            // integral v_h^2 = vv_qq q~^2 + 2 vv_qv q~ v~ + vv_vv v~^2
    Eigen::ArrayXd cos_q, cos_v, sin_q, sin_v;     // integral {cos, sin}(Omega s) v_h(s) ds = _q q~ + _v v~
    double cos_cos = 0, cos_sin = 0, sin_sin = 0;  // integrals of cos^2, cos sin, sin^2 (Omega s)
  };
  // least_panels: the quadrature's panels are at most 1/8 of the fastest period and at least this many (an
  // interval no longer than the fine grid's needs one: its 20-point rule is exact to rounding there).
  EnergyForms energy_forms(double tau_s, int least_panels = 16) const;

  // An upper bound, valid for all later times of free flight, on |sum_{m in [first, last)} lever_m q_m(t)|
  // from the state at t0: each mode's steady-state amplitude plus the envelope of its decaying
  // free motion. Lets the solver step over stretches where the fast modes cannot close the gap.
  double displacement_bound(const ModalState& x0, const MotorPhase& phase, const Eigen::VectorXd& lever, int first,
                            int last) const;
  // The same for |sum lever_m v_m(t)|: how fast those modes can move the tips, for all later times of free flight.
  double speed_bound(const ModalState& x0, const MotorPhase& phase, const Eigen::VectorXd& lever) const;

  // The forms over 2 tau from those over tau (and the transition over tau): [0, tau] and [tau, 2 tau], the
  // second half's free motion starting from the transition of the first's and the motor tau further on.
  // Exact to rounding, where a quadrature over a long interval would need panels on every fast period.
  EnergyForms doubled(const EnergyForms& forms, const Transition& transition) const;

 private:
  void transition_into(double tau_s, Transition& t) const;

  const ModalModel& model_;
  mutable Transition scratch_;
  Eigen::ArrayXd decay_;                    // -zeta omega [1/s]
  Eigen::ArrayXd two_zeta_omega_;           // 2 zeta omega [1/s], the structural damping per unit velocity
  Eigen::ArrayXd oscillation_;              // omega sqrt(|1 - zeta^2|) [rad/s]
  Eigen::ArrayXi regime_;                   // -1 under-, 0 critically, +1 over-damped
  Eigen::ArrayXd forced_cos_, forced_sin_;  // q_p = forced_cos cos(Omega t) - forced_sin sin(Omega t)
};

}  // namespace ib
