#include "physics/beam_modes.h"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ib {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The characteristic equation divided by cosh(lambda): same roots, bounded for every lambda.
double scaled_characteristic(double lambda, double mu) {
  return 1.0 / std::cosh(lambda) + std::cos(lambda) +
         mu * lambda * (std::cos(lambda) * std::tanh(lambda) - std::sin(lambda));
}

}  // namespace

std::vector<double> cantilever_tip_mass_roots(double mass_ratio, int count) {
  if (count < 1 || count > 200) throw std::invalid_argument("mode count must be 1..200, got " + std::to_string(count));
  if (!(mass_ratio >= 0)) throw std::invalid_argument("tip mass ratio must be >= 0");
  std::vector<double> roots;
  // Roots lie about pi apart (one in each ((n-1) pi, n pi)); a pi/64 grid cannot hold two of them.
  const double step = kPi / 64;
  double a = 0, fa = scaled_characteristic(0, mass_ratio);  // = 2 > 0
  for (int i = 1; static_cast<int>(roots.size()) < count; ++i) {
    const double b = i * step;
    const double fb = scaled_characteristic(b, mass_ratio);
    if (fb == 0) {
      roots.push_back(b);
    } else if ((fa < 0) != (fb < 0) && fa != 0) {
      std::uintmax_t iterations = 100;
      const auto bracket =
          boost::math::tools::toms748_solve([mass_ratio](double x) { return scaled_characteristic(x, mass_ratio); }, a,
                                            b, fa, fb, boost::math::tools::eps_tolerance<double>(53), iterations);
      roots.push_back(0.5 * (bracket.first + bracket.second));
    }
    a = b;
    fa = fb;
  }
  return roots;
}

CantileverModes::CantileverModes(const FrameSpec& frame, int count, BeamShapes shapes)
    : frame_(frame), shapes_(shapes) {
  const double L = frame.length_m;
  const double rho_a = frame.mass_per_length_kg_m();
  const double ei = frame.bending_stiffness_n_m2();
  const double mu = frame.tip_mass_kg / (rho_a * L);
  const auto roots = cantilever_tip_mass_roots(mu, count);
  modes_.resize(roots.size());
  for (std::size_t n = 0; n < roots.size(); ++n) {
    Mode& m = modes_[n];
    const double l = roots[n];
    m.lambda = l;
    m.beta_per_m = l / L;
    m.omega_rad_s = l * l * std::sqrt(ei / (rho_a * L * L * L * L));
    const double em = std::exp(-l);
    if (shapes == BeamShapes::corrected) {
      // s = (cosh l + cos l) / (sinh l + sin l), so (1 - s) e^l / 2 = (sin l - cos l - e^-l) / (1 - e^-2l + 2 sin l
      // e^-l)
      m.a = (std::sin(l) - std::cos(l) - em) / (1 - em * em + 2 * std::sin(l) * em);
    } else {
      // s = (sinh l - sin l) / (cosh l + cos l), so (1 - s) e^l / 2 = (e^-l + cos l + sin l) / (1 + e^-2l + 2 cos l
      // e^-l)
      m.a = (em + std::cos(l) + std::sin(l)) / (1 + em * em + 2 * std::cos(l) * em);
    }
    m.s = 1 - 2 * m.a * em;
    m.b = 0.5 * (1 + m.s);
    m.amplitude = 1;
  }
  for (std::size_t n = 0; n < modes_.size(); ++n) {
    Mode& m = modes_[n];
    if (shapes == BeamShapes::corrected) {
      const double tip = shape_derivative(static_cast<int>(n), L, 0);  // with C = 1
      const double norm2 =
          rho_a * integral_of_product(static_cast<int>(n), static_cast<int>(n)) + frame.tip_mass_kg * tip * tip;
      m.amplitude = 1 / std::sqrt(norm2);
    } else {
      m.amplitude = 1 / std::sqrt(rho_a * L);
    }
  }
}

double CantileverModes::shape_derivative(int n, double x_m, int order) const {
  const Mode& m = modes_.at(n);
  const double xi = m.beta_per_m * x_m;
  const double sign = (order % 2 == 0) ? 1.0 : -1.0;
  const double phase = xi + order * kPi / 2;
  const double value =
      m.a * std::exp(xi - m.lambda) + sign * m.b * std::exp(-xi) - std::cos(phase) + m.s * std::sin(phase);
  return m.amplitude * std::pow(m.beta_per_m, order) * value;
}

double CantileverModes::shape(int n, double x_m) const { return shape_derivative(n, x_m, 0); }
double CantileverModes::shape_slope(int n, double x_m) const { return shape_derivative(n, x_m, 1); }
double CantileverModes::shape_curvature(int n, double x_m) const { return shape_derivative(n, x_m, 2); }
double CantileverModes::shape_third_derivative(int n, double x_m) const { return shape_derivative(n, x_m, 3); }

double CantileverModes::integral_of_product(int m, int n) const {
  // Panels of at most a quarter wavelength of the faster shape; 20-point Gauss on each.
  const double L = frame_.length_m;
  const double lambda_max = std::max(modes_.at(m).lambda, modes_.at(n).lambda);
  const int panels = std::max(4, static_cast<int>(std::ceil(2 * lambda_max / kPi)) * 4);
  const double width = L / panels;
  const double cm = modes_[m].amplitude, cn = modes_[n].amplitude;
  auto integrand = [&](double x) { return shape(m, x) / cm * shape(n, x) / cn; };
  double sum = 0;
  for (int p = 0; p < panels; ++p)
    sum += boost::math::quadrature::gauss<double, 20>::integrate(integrand, p * width, (p + 1) * width);
  return sum;
}

double CantileverModes::mass_inner_product(int m, int n) const {
  const double rho_a = frame_.mass_per_length_kg_m();
  return rho_a * modes_.at(m).amplitude * modes_.at(n).amplitude * integral_of_product(m, n) +
         frame_.tip_mass_kg * tip_value(m) * tip_value(n);
}

ModalBasis CantileverModes::basis() const {
  ModalBasis basis;
  const int count = size();
  basis.omega_rad_s.resize(count);
  basis.zeta.setConstant(count, frame_.damping_ratio);
  basis.tip.resize(count);
  for (int n = 0; n < count; ++n) {
    basis.omega_rad_s[n] = modes_[n].omega_rad_s;
    basis.tip[n] = tip_value(n);
  }
  basis.origin =
      std::string(shapes_ == BeamShapes::corrected ? "beam" : "beam (paper eq. 2.5)") + " N=" + std::to_string(count);
  return basis;
}

double ModalBasis::tip_static_compliance_m_per_n() const {
  return (tip.array().square() / omega_rad_s.array().square()).sum();
}

}  // namespace ib
