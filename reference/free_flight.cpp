#include "free_flight.h"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace ib {

FreeFlight::FreeFlight(const ModalModel& model) : model_(model) {
  const int n = model.mode_count();
  const Eigen::ArrayXd omega = model.omega_rad_s.array(), zeta = model.zeta.array();
  decay_ = -zeta * omega;
  oscillation_ = omega * (1 - zeta.square()).abs().sqrt();
  regime_.resize(n);
  for (int m = 0; m < n; ++m) regime_[m] = zeta[m] < 1 ? -1 : (zeta[m] > 1 ? 1 : 0);
  forced_cos_.setZero(n);
  forced_sin_.setZero(n);
  if (model.motor) {
    const double w = model.motor->omega_rad_s;
    for (int m = 0; m < n; ++m) {
      // q_p = Re(H F e^{i Omega t}) with H = p / (omega^2 - Omega^2 + 2 i zeta omega Omega)
      const std::complex<double> denominator(omega[m] * omega[m] - w * w, 2 * zeta[m] * omega[m] * w);
      if (std::abs(denominator) == 0)
        throw std::invalid_argument("mode " + std::to_string(m) + " is undamped and driven exactly at resonance: "
                                    "no steady state exists (give the frame some damping)");
      const std::complex<double> h = model.motor_lever[m] * model.motor->amplitude_n / denominator;
      forced_cos_[m] = h.real();
      forced_sin_[m] = h.imag();
    }
  }
}

FreeFlight::Transition FreeFlight::transition(double tau) const {
  const int n = model_.mode_count();
  Transition t;
  t.tau_s = tau;
  t.qq.resize(n); t.qv.resize(n); t.vq.resize(n); t.vv.resize(n);
  for (int m = 0; m < n; ++m) {
    // exp(A tau) = e^{sigma tau} [C I + S (A - sigma I)], A - sigma I = [[zeta w, 1], [-w^2, -zeta w]]
    const double sigma = decay_[m], w = model_.omega_rad_s[m], zw = -sigma;
    double ec, es;  // e^{sigma tau} C and e^{sigma tau} S, formed without overflow
    if (regime_[m] < 0) {
      const double e = std::exp(sigma * tau), wd = oscillation_[m];
      ec = e * std::cos(wd * tau);
      es = e * std::sin(wd * tau) / wd;
    } else if (regime_[m] > 0) {
      const double k = oscillation_[m];
      const double fast = std::exp((sigma - k) * tau), slow = std::exp((sigma + k) * tau);
      ec = 0.5 * (slow + fast);
      es = 0.5 * (slow - fast) / k;
    } else {
      const double e = std::exp(sigma * tau);
      ec = e;
      es = e * tau;
    }
    t.qq[m] = ec + es * zw;
    t.qv[m] = es;
    t.vq[m] = -es * w * w;
    t.vv[m] = ec - es * zw;
  }
  return t;
}

void FreeFlight::steady_state(double t, ModalState& x) const {
  if (!model_.motor) {
    x.q.setZero(model_.mode_count());
    x.v.setZero(model_.mode_count());
    return;
  }
  const double w = model_.motor->omega_rad_s, c = std::cos(w * t), s = std::sin(w * t);
  x.q = (forced_cos_ * c - forced_sin_ * s).matrix();
  x.v = (-w * (forced_cos_ * s + forced_sin_ * c)).matrix();
}

void FreeFlight::advance(const Transition& tr, const ModalState& x0, double t0, ModalState& x) const {
  if (!model_.motor) {
    const Eigen::ArrayXd q = x0.q.array(), v = x0.v.array();
    x.q = (tr.qq * q + tr.qv * v).matrix();
    x.v = (tr.vq * q + tr.vv * v).matrix();
    return;
  }
  ModalState p0, p1;
  steady_state(t0, p0);
  steady_state(t0 + tr.tau_s, p1);
  const Eigen::ArrayXd q = x0.q.array() - p0.q.array(), v = x0.v.array() - p0.v.array();
  x.q = p1.q + (tr.qq * q + tr.qv * v).matrix();
  x.v = p1.v + (tr.vq * q + tr.vv * v).matrix();
}

}  // namespace ib
