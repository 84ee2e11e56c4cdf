// Modes of the clamped-free beam with a tip mass against closed-form results (rig.md section 2).
#include "physics/beam_modes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/scenario.h"

namespace ib {
namespace beam_modes_test {

constexpr double kPi = 3.14159265358979323846;

TEST(BeamModes, BareCantileverRootsAreTheTextbookValues) {
  const auto roots = cantilever_tip_mass_roots(0.0, 3);
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_NEAR(roots[0], 1.8751041, 1e-7);
  EXPECT_NEAR(roots[1], 4.6940911, 1e-7);
  EXPECT_NEAR(roots[2], 7.8547574, 1e-7);
}

TEST(BeamModes, FirstFrequencyMatchesRayleighWithTheTipMass) {
  for (const FrameSpec& frame : default_rig().frames) {
    const CantileverModes modes(frame, 3);
    const double ei = frame.bending_stiffness_n_m2(), rho_a = frame.mass_per_length_kg_m(), L = frame.length_m;
    const double rayleigh = std::sqrt(3 * ei / ((frame.tip_mass_kg + 0.2357 * rho_a * L) * L * L * L));
    EXPECT_NEAR(modes.omega_rad_s(0) / rayleigh, 1.0, 0.01);
  }
  // and the rig's quoted value: frame 1 at about 6.95 Hz
  EXPECT_NEAR(CantileverModes(default_rig().frames[0], 1).omega_rad_s(0) / (2 * kPi), 6.95, 0.005);
}

TEST(BeamModes, TwentyModesAreOrthonormalWithTheTipMass) {
  const CantileverModes modes(default_rig().frames[0], 20);
  for (int m = 0; m < 20; ++m)
    for (int n = m; n < 20; ++n)
      EXPECT_NEAR(modes.mass_inner_product(m, n), m == n ? 1.0 : 0.0, 1e-10) << "modes " << m + 1 << ", " << n + 1;
}

// No root missed or repeated: one root in each ((n-1) pi, n pi), and a scan eight times finer than the
// solver's finds no other sign change below the last root.
TEST(BeamModes, RootsAreNeitherMissedNorRepeatedForAnyMassRatio) {
  for (double mu : {0.0, 0.01, 0.3, 1.0259, 10.0, 1000.0}) {
    const auto roots = cantilever_tip_mass_roots(mu, 60);
    ASSERT_EQ(roots.size(), 60u);
    for (int n = 0; n < 60; ++n) {
      EXPECT_GT(roots[n], n * kPi) << "mu " << mu << " root " << n + 1;
      EXPECT_LT(roots[n], (n + 1) * kPi) << "mu " << mu << " root " << n + 1;
    }
    auto f = [mu](double l) {
      return 1 / std::cosh(l) + std::cos(l) + mu * l * (std::cos(l) * std::tanh(l) - std::sin(l));
    };
    int changes = 0;
    const double step = kPi / 512;
    for (double l = step; l <= roots.back() + step; l += step)
      if ((f(l - step) < 0) != (f(l) < 0)) ++changes;
    EXPECT_EQ(changes, 60) << "mu " << mu;
  }
}

// The corrected shape satisfies the tip's boundary conditions: zero moment, and the shear force
// carrying the tip mass's inertia, EI phi'''(L) = -M_t omega^2 phi(L).
TEST(BeamModes, CorrectedShapesSatisfyTheTipBoundaryConditions) {
  const FrameSpec frame = default_rig().frames[0];
  const CantileverModes modes(frame, 10);
  const double ei = frame.bending_stiffness_n_m2(), L = frame.length_m;
  for (int n = 0; n < 10; ++n) {
    const double scale = std::pow(modes.lambda(n) / L, 2) * std::abs(modes.tip_value(n));
    EXPECT_NEAR(modes.shape_curvature(n, L) / scale, 0.0, 1e-9) << "mode " << n + 1;
    const double shear = ei * modes.shape_third_derivative(n, L);
    const double inertia = frame.tip_mass_kg * std::pow(modes.omega_rad_s(n), 2) * modes.tip_value(n);
    EXPECT_NEAR(shear / inertia, -1.0, 1e-9) << "mode " << n + 1;
    EXPECT_NEAR(modes.shape(n, 0), 0.0, 1e-12);
    EXPECT_NEAR(modes.shape_slope(n, 0) / (modes.lambda(n) / L * std::abs(modes.tip_value(n))), 0.0, 1e-9);
  }
}

// The paper's eq. 2.5 as rig.md section 6.1 describes it: phi_1(L)^2 overstated about 2.4x and
// phi_2(L)^2 about 30x for frame 1.
TEST(BeamModes, PaperShapesOverstateTheTipValuesAsDocumented) {
  const FrameSpec frame = default_rig().frames[0];
  const CantileverModes corrected(frame, 3), paper(frame, 3, BeamShapes::paper_eq_2_5);
  auto ratio = [&](int n) { return std::pow(paper.tip_value(n) / corrected.tip_value(n), 2); };
  EXPECT_NEAR(ratio(0), 2.4, 0.1);
  EXPECT_NEAR(ratio(1), 30, 2);
  EXPECT_GT(ratio(2), 30);
  for (int n = 0; n < 3; ++n) EXPECT_DOUBLE_EQ(paper.omega_rad_s(n), corrected.omega_rad_s(n));
}

// The undamped tip receptance of the continuous beam (closed form, no modes) equals the sum over
// the modes, sum phi_n(L)^2 / (omega_n^2 - Omega^2): checks frequencies and tip values together.
TEST(BeamModes, ModalSumConvergesToTheContinuousTipReceptance) {
  const FrameSpec frame = default_rig().frames[0];
  const double ei = frame.bending_stiffness_n_m2(), rho_a = frame.mass_per_length_kg_m(), L = frame.length_m;
  const CantileverModes modes(frame, 60);
  for (double omega : {5.0, 60.0, 800.0, 3000.0}) {
    // w = A (cosh - cos) + B (sinh - sin); w''(L) = 0; EI w'''(L) = -(F + M_t Omega^2 w(L)), F = 1
    const double beta = std::pow(rho_a * omega * omega / ei, 0.25), l = beta * L;
    const double ch = std::cosh(l), c = std::cos(l), sh = std::sinh(l), s = std::sin(l);
    // unknowns A, B: row 1 moment, row 2 shear
    const double a11 = ch + c, a12 = sh + s;
    const double a21 = ei * beta * beta * beta * (sh - s) + frame.tip_mass_kg * omega * omega * (ch - c);
    const double a22 = ei * beta * beta * beta * (ch + c) + frame.tip_mass_kg * omega * omega * (sh - s);
    const double det = a11 * a22 - a12 * a21;
    const double A = a12 / det, B = -a11 / det;  // Cramer's rule for [a11 a12; a21 a22] [A; B] = [0; -1]
    const double exact = A * (ch - c) + B * (sh - s);
    double modal = 0;
    for (int n = 0; n < modes.size(); ++n)
      modal += std::pow(modes.tip_value(n), 2) / (std::pow(modes.omega_rad_s(n), 2) - omega * omega);
    EXPECT_NEAR(modal / exact, 1.0, 1e-5) << "Omega " << omega << " rad/s";
  }
}

}  // namespace beam_modes_test
}  // namespace ib
