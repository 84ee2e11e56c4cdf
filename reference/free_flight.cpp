#include "reference/free_flight.h"

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace ib {

FreeFlight::FreeFlight(const ModalModel& model) : model_(model) {
  const int n = model.mode_count();
  const Eigen::ArrayXd omega = model.omega_rad_s.array(), zeta = model.zeta.array();
  decay_ = -zeta * omega;
  two_zeta_omega_ = 2 * zeta * omega;
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
        throw std::invalid_argument("mode " + std::to_string(m) +
                                    " is undamped and driven exactly at resonance: "
                                    "no steady state exists (give the frame some damping)");
      const std::complex<double> h = model.motor_lever[m] * model.motor->amplitude_n / denominator;
      forced_cos_[m] = h.real();
      forced_sin_[m] = h.imag();
    }
  }
}

FreeFlight::Transition FreeFlight::transition(double tau) const {
  Transition t;
  transition_into(tau, t);
  return t;
}

void FreeFlight::transition_into(double tau, Transition& t) const {
  const int n = model_.mode_count();
  t.tau_s = tau;
  t.qq.resize(n);
  t.qv.resize(n);
  t.vq.resize(n);
  t.vv.resize(n);
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
}

void FreeFlight::steady_state(double t, ModalState& x) const {
  const int n = model_.mode_count();
  x.q.resize(n);
  x.v.resize(n);
  if (!model_.motor) {
    x.q.setZero();
    x.v.setZero();
    return;
  }
  const double w = model_.motor->omega_rad_s, c = std::cos(w * t), s = std::sin(w * t);
  x.q = (forced_cos_ * c - forced_sin_ * s).matrix();
  x.v = (-w * (forced_cos_ * s + forced_sin_ * c)).matrix();
}

void FreeFlight::free_part(const ModalState& x, const MotorPhase& phase, Eigen::ArrayXd& q_free,
                           Eigen::ArrayXd& v_free) const {
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  q_free = x.q.array() - (forced_cos_ * phase.cos - forced_sin_ * phase.sin);
  v_free = x.v.array() + w * (forced_cos_ * phase.sin + forced_sin_ * phase.cos);
}

void FreeFlight::with_steady_state(const Eigen::ArrayXd& q_free, const Eigen::ArrayXd& v_free, const MotorPhase& phase,
                                   ModalState& x) const {
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  x.q = (q_free + forced_cos_ * phase.cos - forced_sin_ * phase.sin).matrix();
  x.v = (v_free - w * (forced_cos_ * phase.sin + forced_sin_ * phase.cos)).matrix();
}

FreeFlight::MotorPhase FreeFlight::motor_phase(double t) const {
  if (!model_.motor) return {t, 1, 0};
  const double angle = model_.motor->omega_rad_s * t;
  return {t, std::cos(angle), std::sin(angle)};
}

void FreeFlight::advance(const Transition& tr, const MotorPhase& from, const MotorPhase& to, const ModalState& x0,
                         ModalState& x, const EnergyForms* forms, double* motor_work_j,
                         double* structural_dissipation_j) const {
  const int n = model_.mode_count();
  x.q.resize(n);
  x.v.resize(n);
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  const double c0 = from.cos, s0 = from.sin, c1 = to.cos, s1 = to.sin;
  const double motor_force = model_.motor ? model_.motor->amplitude_n : 0;
  double work = 0, dissipation = 0;
  // A plain loop: this is the reference's innermost loop, run millions of times, without temporaries.
  for (int m = 0; m < n; ++m) {
    const double a = forced_cos_[m], b = forced_sin_[m];
    // the free part (x - x_p) at the start, and the steady-state velocity v_p(t0 + s) = P cos + Q sin
    const double p = -w * (a * s0 + b * c0), q = -w * (a * c0 - b * s0);
    const double q_free = x0.q[m] - (a * c0 - b * s0), v_free = x0.v[m] - p;
    x.q[m] = (a * c1 - b * s1) + tr.qq[m] * q_free + tr.qv[m] * v_free;
    x.v[m] = -w * (a * s1 + b * c1) + tr.vq[m] * q_free + tr.vv[m] * v_free;
    if (!forms) continue;
    const EnergyForms& f = *forms;
    const double hom_sq =
        f.vv_qq[m] * q_free * q_free + 2 * f.vv_qv[m] * q_free * v_free + f.vv_vv[m] * v_free * v_free;
    if (w == 0) {  // no motor: the steady state and its cross terms are zero
      dissipation += two_zeta_omega_[m] * hom_sq;
      continue;
    }
    const double cos_hom = f.cos_q[m] * q_free + f.cos_v[m] * v_free;
    const double sin_hom = f.sin_q[m] * q_free + f.sin_v[m] * v_free;
    const double part_sq = p * p * f.cos_cos + 2 * p * q * f.cos_sin + q * q * f.sin_sin;
    dissipation += two_zeta_omega_[m] * (hom_sq + 2 * (p * cos_hom + q * sin_hom) + part_sq);
    if (motor_force != 0 && model_.motor_lever[m] != 0) {
      // F_m(t0 + s) = F (c0 cos(Omega s) - s0 sin(Omega s))
      const double cos_v = p * f.cos_cos + q * f.cos_sin + cos_hom;
      const double sin_v = p * f.cos_sin + q * f.sin_sin + sin_hom;
      work += motor_force * model_.motor_lever[m] * (c0 * cos_v - s0 * sin_v);
    }
  }
  if (forms) {
    *motor_work_j += work;
    *structural_dissipation_j += dissipation;
  }
}

FreeFlight::EnergyForms FreeFlight::energy_forms(double tau, int least_panels) const {
  const int n = model_.mode_count();
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  EnergyForms f;
  f.tau_s = tau;
  for (Eigen::ArrayXd* a : {&f.vv_qq, &f.vv_qv, &f.vv_vv, &f.cos_q, &f.cos_v, &f.sin_q, &f.sin_v}) a->setZero(n);
  // 20-point Gauss-Legendre on panels short against the fastest period: exact to rounding.
  const double fastest_period = 2 * M_PI / model_.omega_rad_s.maxCoeff();
  const int panels = std::max(least_panels, static_cast<int>(std::ceil(8 * tau / fastest_period)));
  const double width = tau / panels;
  const auto& nodes = boost::math::quadrature::gauss<double, 20>::abscissa();
  const auto& weights = boost::math::quadrature::gauss<double, 20>::weights();
  auto add = [&](double s, double weight) {
    const Transition t = transition(s);
    const double c = std::cos(w * s), sn = std::sin(w * s);
    f.vv_qq += weight * t.vq * t.vq;
    f.vv_qv += weight * t.vq * t.vv;
    f.vv_vv += weight * t.vv * t.vv;
    f.cos_q += weight * c * t.vq;
    f.cos_v += weight * c * t.vv;
    f.sin_q += weight * sn * t.vq;
    f.sin_v += weight * sn * t.vv;
    f.cos_cos += weight * c * c;
    f.cos_sin += weight * c * sn;
    f.sin_sin += weight * sn * sn;
  };
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * width, half = 0.5 * width;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      // boost stores the non-negative abscissae; the zero node (odd order only) counts once
      add(mid + half * nodes[i], half * weights[i]);
      if (nodes[i] != 0) add(mid - half * nodes[i], half * weights[i]);
    }
  }
  return f;
}

FreeFlight::EnergyForms FreeFlight::doubled(const EnergyForms& f, const Transition& tr) const {
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  const double c = std::cos(w * f.tau_s), s = std::sin(w * f.tau_s);
  EnergyForms d = f;
  d.tau_s = 2 * f.tau_s;
  for (Eigen::Index m = 0; m < f.vv_qq.size(); ++m) {
    const double qq = tr.qq[m], qv = tr.qv[m], vq = tr.vq[m], vv = tr.vv[m];
    const double a = f.vv_qq[m], b = f.vv_qv[m], e = f.vv_vv[m];
    // the quadratic form of the second half: Phi^T M Phi
    d.vv_qq[m] += a * qq * qq + 2 * b * qq * vq + e * vq * vq;
    d.vv_qv[m] += a * qq * qv + b * (qq * vv + qv * vq) + e * vq * vv;
    d.vv_vv[m] += a * qv * qv + 2 * b * qv * vv + e * vv * vv;
    // the linear forms of the second half on the state at tau, with cos(Omega (tau + u)) = c cos - s sin
    const double cos_q = f.cos_q[m] * qq + f.cos_v[m] * vq, cos_v = f.cos_q[m] * qv + f.cos_v[m] * vv;
    const double sin_q = f.sin_q[m] * qq + f.sin_v[m] * vq, sin_v = f.sin_q[m] * qv + f.sin_v[m] * vv;
    d.cos_q[m] += c * cos_q - s * sin_q;
    d.cos_v[m] += c * cos_v - s * sin_v;
    d.sin_q[m] += s * cos_q + c * sin_q;
    d.sin_v[m] += s * cos_v + c * sin_v;
  }
  d.cos_cos += c * c * f.cos_cos - 2 * c * s * f.cos_sin + s * s * f.sin_sin;
  d.cos_sin += c * s * f.cos_cos + (c * c - s * s) * f.cos_sin - c * s * f.sin_sin;
  d.sin_sin += s * s * f.cos_cos + 2 * s * c * f.cos_sin + c * c * f.sin_sin;
  return d;
}

double FreeFlight::speed_bound(const ModalState& x0, const MotorPhase& phase, const Eigen::VectorXd& lever) const {
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  double bound = 0;
  for (int m = 0; m < model_.mode_count(); ++m) {
    if (lever[m] == 0) continue;
    const double a = forced_cos_[m], b = forced_sin_[m];
    const double q0 = x0.q[m] - (a * phase.cos - b * phase.sin);
    const double v0 = x0.v[m] + w * (a * phase.sin + b * phase.cos);
    const double sigma = decay_[m], k = oscillation_[m], w_m = model_.omega_rad_s[m];
    // the free velocity obeys the mode's own equation, from v0 with the slope a0 = 2 sigma v0 - omega^2 q0:
    // the displacement bound's envelope with (q0, v0) replaced by (v0, a0)
    const double a0 = 2 * sigma * v0 - w_m * w_m * q0;
    double envelope;
    if (regime_[m] < 0) {
      const double s0 = (a0 - sigma * v0) / k;
      envelope = std::sqrt(v0 * v0 + s0 * s0);
    } else {
      const double s_max = regime_[m] > 0 ? std::min(0.5 / k, 1 / (std::exp(1.0) * std::abs(sigma + k)))
                                          : 1 / (std::exp(1.0) * std::abs(sigma));
      envelope = std::abs(v0) + std::abs(a0 - sigma * v0) * s_max;
    }
    bound += std::abs(lever[m]) * (w * std::sqrt(a * a + b * b) + envelope);
  }
  return bound;
}

double FreeFlight::displacement_bound(const ModalState& x0, const MotorPhase& phase, const Eigen::VectorXd& lever,
                                      int first, int last) const {
  const double w = model_.motor ? model_.motor->omega_rad_s : 0;
  double bound = 0;
  for (int m = first; m < last; ++m) {
    const double a = forced_cos_[m], b = forced_sin_[m];
    const double q0 = x0.q[m] - (a * phase.cos - b * phase.sin);
    const double v0 = x0.v[m] + w * (a * phase.sin + b * phase.cos);
    const double sigma = decay_[m], k = oscillation_[m];
    double envelope;
    if (regime_[m] < 0) {
      // e^{sigma t} (q0 cos + (v0 - sigma q0)/w_d sin) never exceeds its amplitude
      const double s0 = (v0 - sigma * q0) / k;
      envelope = std::sqrt(q0 * q0 + s0 * s0);
    } else {
      // |e^{sigma t} C| <= 1 and e^{sigma t} S <= min(1/(2k), 1/(e |sigma + k|)) (t e^{sigma t} for k = 0)
      const double s_max = regime_[m] > 0 ? std::min(0.5 / k, 1 / (std::exp(1.0) * std::abs(sigma + k)))
                                          : 1 / (std::exp(1.0) * std::abs(sigma));
      envelope = std::abs(q0) + std::abs(v0 - sigma * q0) * s_max;
    }
    bound += std::abs(lever[m]) * (std::sqrt(a * a + b * b) + envelope);
  }
  return bound;
}

}  // namespace ib
