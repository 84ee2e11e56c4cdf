// One impact against closed-form contact mechanics: two free masses meet, so the contact is a
// one-degree-of-freedom problem with the reduced mass (rig.md section 3).
#include <gtest/gtest.h>

#include <cmath>

#include "reference_fixtures.h"

namespace ib {
namespace single_impact_test {

using testing::approaching;
using testing::solve;
using testing::two_free_masses;

constexpr double kM1 = 0.64439, kM2 = 0.41380, kApproach = 0.1644;
const double kReducedMass = kM1 * kM2 / (kM1 + kM2);

ReferenceSettings tight() {
  ReferenceSettings s;
  s.relative_tolerance = 1e-11;
  s.absolute_tolerance = 1e-15;
  return s;
}

TEST(SingleImpact, SpringDashpotDurationAndRestitutionAreTheClosedForm) {
  const double k = 6.99e6, c = 170.07;
  const ModalModel model = two_free_masses(kM1, kM2, 1e-6, ViscoelasticLaw{k, c, false});
  const ReferenceSolution r = solve(model, approaching(model, kApproach), 0.01, tight());
  ASSERT_EQ(r.trajectory.events.size(), 1u);
  const ContactEvent& e = r.trajectory.events[0];
  const double omega = std::sqrt(k / kReducedMass), zeta = c / (2 * std::sqrt(k * kReducedMass));
  const double omega_d = omega * std::sqrt(1 - zeta * zeta);
  EXPECT_NEAR((e.end_time_s - e.onset_time_s) / (M_PI / omega_d), 1.0, 1e-8);
  EXPECT_NEAR(e.restitution / std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)), 1.0, 1e-8);
  EXPECT_NEAR(e.approach_velocity_m_s / kApproach, 1.0, 1e-10);
  EXPECT_NEAR(e.onset_time_s / (1e-6 / kApproach), 1.0, 1e-8);
  // impulse = reduced mass x velocity change
  EXPECT_NEAR(e.impulse_n_s / (kReducedMass * (e.approach_velocity_m_s + e.rebound_velocity_m_s)), 1.0, 1e-8);
}

TEST(SingleImpact, ClippedSpringDashpotNeverPulls) {
  const ModalModel model = two_free_masses(kM1, kM2, 1e-6, ViscoelasticLaw{6.99e6, 170.07, true});
  const ReferenceSolution r = solve(model, approaching(model, kApproach), 0.01, tight(), 200000);
  ASSERT_EQ(r.trajectory.events.size(), 1u);
  for (double f : r.trajectory.contact_force_n) EXPECT_GE(f, 0.0);
  // without the tensile tail the tips leave sooner and faster than with the published law
  const ModalModel published = two_free_masses(kM1, kM2, 1e-6, ViscoelasticLaw{6.99e6, 170.07, false});
  const ContactEvent p = solve(published, approaching(published, kApproach), 0.01, tight()).trajectory.events.at(0);
  EXPECT_GT(r.trajectory.events[0].restitution, p.restitution);
}

// Undamped Hertz: delta_max = ((n+1) m v^2 / (2k))^(1/(n+1)) and the duration
// t_c = 2 (delta_max / v) B(1/(n+1), 1/2) / (n+1); for n = 3/2 that is Hertz's 2.9432 delta_max / v.
TEST(SingleImpact, UndampedHertzDurationIsHertzsFormula) {
  for (double n : {1.5, 1.0}) {
    const double k = n == 1.5 ? 2.31e10 : 6.99e6;
    const ModalModel model = two_free_masses(kM1, kM2, 1e-6, HertzLaw{k, n, 0.0});
    const ReferenceSolution r = solve(model, approaching(model, kApproach), 0.01, tight());
    ASSERT_EQ(r.trajectory.events.size(), 1u) << "n = " << n;
    const ContactEvent& e = r.trajectory.events[0];
    const double dmax = std::pow((n + 1) * kReducedMass * kApproach * kApproach / (2 * k), 1 / (n + 1));
    const double a = 1 / (n + 1);
    const double beta = std::tgamma(a) * std::tgamma(0.5) / std::tgamma(a + 0.5);
    const double duration = 2 * dmax / kApproach * beta / (n + 1);
    EXPECT_NEAR((e.end_time_s - e.onset_time_s) / duration, 1.0, 1e-8) << "n = " << n;
    EXPECT_NEAR(e.max_indentation_m / dmax, 1.0, 1e-8) << "n = " << n;
    EXPECT_NEAR(e.restitution, 1.0, 1e-8) << "n = " << n;
    EXPECT_NEAR(e.peak_force_n / (k * std::pow(dmax, n)), 1.0, 1e-8) << "n = " << n;
  }
  // the 3/2 constant
  const double a = 0.4;
  EXPECT_NEAR(2 * std::tgamma(a) * std::tgamma(0.5) / std::tgamma(a + 0.5) / 2.5, 2.9432, 1e-4);
}

// Hunt-Crossley damping calibrated by Lankarani-Nikravesh realises about e for e near 1.
// The same impact a hundred seconds into a run, as the published cases' impacts are: its largest indentation and
// force are located within the contact as precisely as at t = 0 (in the contact's own time, not the run's clock).
TEST(SingleImpact, ALateImpactsPeakIsAsPreciseAsAnEarlyOnes) {
  const double k = 2.31e10, n = 1.5, onset_s = 100;
  const ModalModel model = two_free_masses(kM1, kM2, kApproach * onset_s, HertzLaw{k, n, 0.0});
  const ReferenceSolution r = solve(model, approaching(model, kApproach), onset_s + 0.01, tight(), 10);
  ASSERT_EQ(r.trajectory.events.size(), 1u);
  const ContactEvent& e = r.trajectory.events[0];
  ASSERT_GT(e.onset_time_s, 0.99 * onset_s);
  // the "structure" of the free masses, slow as it is, has changed the approach a little over 100 s: the closed
  // form with the approach velocity the contact met
  const double v = e.approach_velocity_m_s;
  const double dmax = std::pow((n + 1) * kReducedMass * v * v / (2 * k), 1 / (n + 1));
  EXPECT_NEAR(e.max_indentation_m / dmax, 1.0, 1e-8);
  EXPECT_NEAR(e.peak_force_n / (k * std::pow(dmax, n)), 1.0, 1e-8);
}

TEST(SingleImpact, HertzDampingRealisesTheCalibratedRestitutionNearOne) {
  const double k = 2.31e10, e_target = 0.95;
  const double c = 3 * k * (1 - e_target * e_target) / (4 * kApproach);
  const ModalModel model = two_free_masses(kM1, kM2, 1e-6, HertzLaw{k, 1.5, c});
  const ReferenceSolution r = solve(model, approaching(model, kApproach), 0.01, tight());
  ASSERT_EQ(r.trajectory.events.size(), 1u);
  EXPECT_NEAR(r.trajectory.events[0].restitution, e_target, 0.01);
}

TEST(SingleImpact, NewtonLawRealisesExactlyE) {
  for (double e : {0.0, 0.3, 0.8, 1.0}) {
    const ModalModel model = two_free_masses(kM1, kM2, 1e-6, NewtonLaw{e});
    ReferenceSettings settings;
    settings.accumulation_time_s = 0;  // free masses: nothing pushes them back together
    const ReferenceSolution r = solve(model, approaching(model, kApproach), 0.01, settings);
    ASSERT_EQ(r.trajectory.events.size(), 1u) << "e = " << e;
    const ContactEvent& ev = r.trajectory.events[0];
    EXPECT_NEAR(ev.rebound_velocity_m_s, e * kApproach, 1e-12) << "e = " << e;
    // and in the state: the relative tip velocity after the impact (last sample) is -e v
    const auto& v1 = r.trajectory.velocity_m_s[0];
    const auto& v2 = r.trajectory.velocity_m_s[1];
    EXPECT_NEAR(v1.back() - v2.back(), -e * kApproach, 1e-12) << "e = " << e;
    // momentum is conserved
    EXPECT_NEAR(kM1 * v1.back() + kM2 * v2.back(), kM1 * kApproach, 1e-12) << "e = " << e;
  }
}

// A contact whose whole indentation (a picometre) lies between two grid points is still found: the
// indentation's maximum between grid points is checked.
TEST(SingleImpact, GrazingContactBetweenGridPointsIsNotMissed) {
  for (double overlap : {1e-12, -1e-12}) {
    ModalModel model;
    const double omega = 2 * M_PI * 7, amplitude = 2e-3;
    for (int f = 0; f < 2; ++f) {
      model.frames[f].omega_rad_s = Eigen::VectorXd::Constant(1, f == 0 ? omega : 2 * M_PI * 8);
      model.frames[f].zeta = Eigen::VectorXd::Zero(1);
      model.frames[f].tip = Eigen::VectorXd::Ones(1);
    }
    model.gap_m = amplitude - overlap;
    model.contact = HertzLaw{2.31e10, 1.5, 0};
    model.finalise();
    ModalState x{Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)};
    x.q[0] = -amplitude;  // released from -A: reaches +A at T/2
    ReferenceSettings settings;
    settings.grid_points_per_period = 7;  // T/2 falls halfway between grid points 3 and 4
    settings.slow_modes_per_frame = 0;
    const ReferenceSolution r = solve(model, x, 0.6 * 2 * M_PI / omega, settings);
    EXPECT_EQ(r.trajectory.events.size(), overlap > 0 ? 1u : 0u) << "overlap " << overlap;
    if (overlap > 0 && !r.trajectory.events.empty()) {
      EXPECT_NEAR(r.trajectory.events[0].onset_time_s, M_PI / omega, 1e-6);
      EXPECT_GT(r.trajectory.events[0].max_indentation_m, 0.0);
      EXPECT_LT(r.trajectory.events[0].max_indentation_m, 2 * overlap);
    }
  }
}

}  // namespace single_impact_test
}  // namespace ib
