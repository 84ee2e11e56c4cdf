// Modes of a clamped-free Euler-Bernoulli beam with a rigid tip mass (rig.md section 2).
//
// With mu = M_t / (rho A L) and lambda = beta L, the roots of
//   1 + cos(lambda) cosh(lambda) + mu lambda (cos(lambda) sinh(lambda) - sin(lambda) cosh(lambda)) = 0
// give omega_n = lambda_n^2 sqrt(EI / (rho A L^4)), and the shape that satisfies zero moment at the tip is
//   phi_n(x) = C_n [cosh(beta x) - cos(beta x) - s_n (sinh(beta x) - sin(beta x))],
//   s_n = (cosh lambda + cos lambda) / (sinh lambda + sin lambda),
// normalised so that integral rho A phi_n^2 dx + M_t phi_n(L)^2 = 1.
#pragma once

#include <vector>

#include "model/scenario.h"
#include "physics/modal_basis.h"

namespace ib {

// The shape family. paper_eq_2_5 reproduces the publication (rig.md section 6.1): the tip-mass roots
// with the bare cantilever's shape constant s_n = (sinh lambda - sin lambda) / (cosh lambda + cos lambda)
// and C_n = 1 / sqrt(rho A L), the bare cantilever's normalisation, which ignores the tip mass. Read
// that way, eq. 2.5 overstates phi_n(L)^2 of frame 1 by 2.4x, 29x and 69x for n = 1, 2, 3.
enum class BeamShapes { corrected, paper_eq_2_5 };

// The first `count` roots lambda_n of the characteristic equation for mass ratio mu = M_t/(rho A L),
// ascending, each to full double precision. Found by bracketing sign changes of the equation divided
// by cosh(lambda) on a grid of pi/64 (roots are about pi apart), then TOMS 748.
std::vector<double> cantilever_tip_mass_roots(double mass_ratio, int count);

class CantileverModes {
 public:
  CantileverModes(const FrameSpec& frame, int count, BeamShapes shapes = BeamShapes::corrected);

  int size() const { return static_cast<int>(modes_.size()); }
  double lambda(int n) const { return modes_[n].lambda; }            // beta_n L [-]
  double omega_rad_s(int n) const { return modes_[n].omega_rad_s; }  // [rad/s]
  double shape(int n, double x_m) const;                             // phi_n(x) [1/sqrt(kg)]
  double shape_slope(int n, double x_m) const;                       // phi_n'(x) [1/(sqrt(kg) m)]
  double shape_curvature(int n, double x_m) const;                   // phi_n''(x) [1/(sqrt(kg) m^2)]
  double shape_third_derivative(int n, double x_m) const;            // phi_n'''(x) [1/(sqrt(kg) m^3)]
  double tip_value(int n) const { return shape(n, frame_.length_m); }
  // integral_0^L rho A phi_m phi_n dx + M_t phi_m(L) phi_n(L): the inner product the modes are
  // orthonormal in (corrected shapes only) [-]. Gauss-Legendre on panels fine enough for mode count.
  double mass_inner_product(int m, int n) const;

  // omega, tip values and the frame's damping ratio on every mode.
  ModalBasis basis() const;

 private:
  // phi/C = A e^(xi - lambda) + B e^(-xi) - cos xi + s sin xi with xi = beta x: the cosh/sinh terms
  // rewritten so that nothing overflows or cancels for large lambda (A = (1 - s) e^lambda / 2 = O(1)).
  struct Mode {
    double lambda = 0, beta_per_m = 0, omega_rad_s = 0;
    double s = 0, a = 0, b = 0;  // shape constant s and the stable coefficients A, B = (1 + s) / 2
    double amplitude = 0;        // C_n [1/sqrt(kg)]
  };
  double shape_derivative(int n, double x_m, int order) const;
  double integral_of_product(int m, int n) const;  // integral_0^L phi_m phi_n dx / (C_m C_n)

  FrameSpec frame_;
  BeamShapes shapes_;
  std::vector<Mode> modes_;
};

}  // namespace ib
