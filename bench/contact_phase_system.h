// The equations of one compliant contact phase, as reference/contact_phase.cpp integrates them, for
// bench/contact_integrators.cpp to hand to several Boost.Odeint steppers:
//
//   y = [q (M), v (M), motor work, structural dissipation, contact dissipation, impulse]
//   q' = v,   v' = p F_m(t) - 2 zeta omega v - omega^2 q - b F_c(delta, delta'),   delta = b . q - gap
//
// The four integrals ride along in the state as they do in the reference, so that every stepper's error
// control sees the same vector the reference's Dormand-Prince sees. The Jacobian (for rosenbrock4) is
// exact: the only coupling between modes is the contact force, a function of delta and delta' alone.
//
// Time runs from the contact's onset (t = time_origin_s + tau): the stepper's times, and the root searches on
// them, then resolve a contact of microseconds to its own scale, not to the run's (an event time of 100 s
// located to 50 bits is only good to 1.8e-13 s, 1e-9 of a 160 us contact; an extremum's to 26 bits, far worse).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <boost/numeric/ublas/matrix.hpp>
#include <boost/numeric/ublas/vector.hpp>
#include <cmath>
#include <variant>

#include "physics/contact_laws.h"
#include "physics/modal_model.h"

namespace ib::bench {

// The relative motion of the tips and the force between them at one state.
struct ContactKinematics {
  double indentation = 0, indentation_rate = 0, force = 0, force_rate = 0;
};

// dF_c/d delta and dF_c/d delta' of the continued law (physics/contact_laws.cpp, contact_force_continued),
// and the slope of its elastic part: what the Jacobian needs.
struct ForceSlopes {
  double d_indentation = 0, d_rate = 0, elastic_d_indentation = 0;
};

class ContactPhaseSystem {
 public:
  explicit ContactPhaseSystem(const ModalModel& model) : model_(model), m_(model.mode_count()) {
    stiffness_ = model.omega_rad_s.array().square();
    damping_rate_ = 2 * model.zeta.array() * model.omega_rad_s.array();
    lever_norm2_ = model.contact_lever.squaredNorm();
  }

  int modes() const { return m_; }
  int size() const { return 2 * m_ + 4; }
  int impulse_index() const { return 2 * m_ + 3; }
  double motor(double tau) const { return model_.motor ? model_.motor->at(time_origin_s + tau) : 0; }
  double motor_rate(double tau) const { return model_.motor ? model_.motor->rate_at(time_origin_s + tau) : 0; }
  mutable double time_origin_s = 0;  // the current contact's onset [s]

  ContactKinematics kinematics(const double* y, double t) const {
    const double* q = y;
    const double* v = y + m_;
    const double f_m = motor(t);
    const double* b = model_.contact_lever.data();
    const double* p = model_.motor_lever.data();
    double delta = -model_.gap_m, rate = 0, lever_driven = 0;
    for (int m = 0; m < m_; ++m) {
      delta += b[m] * q[m];
      rate += b[m] * v[m];
      lever_driven += b[m] * (p[m] * f_m - damping_rate_[m] * v[m] - stiffness_[m] * q[m]);
    }
    ContactKinematics k;
    k.indentation = delta;
    k.indentation_rate = rate;
    k.force = contact_force_continued(model_.contact, delta, rate);
    // delta'' = b . (driven - b F): what the force's rate needs besides delta and delta'
    k.force_rate = contact_force_rate(model_.contact, delta, rate, lever_driven - lever_norm2_ * k.force);
    return k;
  }

  // The right-hand side for any state type with operator[] (std::vector, ublas::vector).
  template <class State>
  void rhs(const State& y, State& dy, double t) const {
    ++rhs_calls;
    const double f_m = motor(t);
    const double* b = model_.contact_lever.data();
    const double* p = model_.motor_lever.data();
    double delta = -model_.gap_m, rate = 0, motor_power = 0, structural_power = 0;
    for (int m = 0; m < m_; ++m) {
      delta += b[m] * y[m];
      rate += b[m] * y[m_ + m];
    }
    const double force = contact_force_continued(model_.contact, delta, rate);
    for (int m = 0; m < m_; ++m) {
      const double v = y[m_ + m];
      dy[m] = v;
      dy[m_ + m] = p[m] * f_m - damping_rate_[m] * v - stiffness_[m] * y[m] - b[m] * force;
      motor_power += p[m] * v;
      structural_power += damping_rate_[m] * v * v;
    }
    dy[2 * m_] = f_m * motor_power;
    dy[2 * m_ + 1] = structural_power;
    dy[2 * m_ + 2] = (force - elastic_contact_force(model_.contact, delta)) * rate;
    dy[2 * m_ + 3] = force;
  }

  ForceSlopes slopes(double delta, double rate) const {
    ForceSlopes s;
    if (const auto* h = std::get_if<HertzLaw>(&model_.contact)) {
      const double factor = 1 + h->damping / h->stiffness * rate;
      const double magnitude = std::abs(delta);
      const double spring_slope = h->stiffness * h->exponent * std::pow(magnitude, h->exponent - 1);
      if (factor > 0) {
        s.d_indentation = spring_slope * factor;
        s.d_rate = h->damping * std::copysign(std::pow(magnitude, h->exponent), delta);
      }
      if (delta > 0) s.elastic_d_indentation = spring_slope;
    } else if (const auto* v = std::get_if<ViscoelasticLaw>(&model_.contact)) {
      const bool clipped = v->clip_tension && v->stiffness_n_per_m * delta + v->damping_n_s_per_m * rate <= 0;
      if (!clipped) s.d_indentation = v->stiffness_n_per_m, s.d_rate = v->damping_n_s_per_m;
      if (delta > 0) s.elastic_d_indentation = v->stiffness_n_per_m;
    }
    return s;
  }

  // J = d rhs / d y and d rhs / d t, in the form odeint's rosenbrock4 asks for.
  void jacobian(const boost::numeric::ublas::vector<double>& y, boost::numeric::ublas::matrix<double>& J, double t,
                boost::numeric::ublas::vector<double>& dfdt) const {
    ++jacobian_calls;
    const double* b = model_.contact_lever.data();
    const double* p = model_.motor_lever.data();
    double delta = -model_.gap_m, rate = 0, motor_power = 0;
    for (int m = 0; m < m_; ++m) {
      delta += b[m] * y[m];
      rate += b[m] * y[m_ + m];
      motor_power += p[m] * y[m_ + m];
    }
    const double force = contact_force_continued(model_.contact, delta, rate);
    const double elastic = elastic_contact_force(model_.contact, delta);
    const ForceSlopes s = slopes(delta, rate);
    const double motor_rate = this->motor_rate(t), f_m = motor(t);
    J.clear();
    const int v0 = m_, work = 2 * m_, structural = 2 * m_ + 1, dissipation = 2 * m_ + 2, impulse = 2 * m_ + 3;
    for (int m = 0; m < m_; ++m) {
      J(m, v0 + m) = 1;
      for (int j = 0; j < m_; ++j) {  // the contact force couples every mode through delta and delta'
        J(v0 + m, j) = -b[m] * s.d_indentation * b[j];
        J(v0 + m, v0 + j) = -b[m] * s.d_rate * b[j];
      }
      J(v0 + m, m) -= stiffness_[m];
      J(v0 + m, v0 + m) -= damping_rate_[m];
      J(work, v0 + m) = f_m * p[m];
      J(structural, v0 + m) = 2 * damping_rate_[m] * y[m_ + m];
      J(dissipation, m) = (s.d_indentation - s.elastic_d_indentation) * b[m] * rate;
      J(dissipation, v0 + m) = s.d_rate * b[m] * rate + (force - elastic) * b[m];
      J(impulse, m) = s.d_indentation * b[m];
      J(impulse, v0 + m) = s.d_rate * b[m];
      dfdt[m] = 0;
      dfdt[v0 + m] = p[m] * motor_rate;
    }
    dfdt[work] = motor_rate * motor_power;
    dfdt[structural] = dfdt[dissipation] = dfdt[impulse] = 0;
  }

  mutable long long rhs_calls = 0, jacobian_calls = 0;

 private:
  const ModalModel& model_;
  int m_;
  Eigen::ArrayXd stiffness_, damping_rate_;  // omega^2 [1/s^2], 2 zeta omega [1/s]
  double lever_norm2_ = 0;
};

}  // namespace ib::bench
