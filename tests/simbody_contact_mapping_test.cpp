// The Simbody contact mapping's physics in one place (adapters/simbody/simbody_contact.h):
//  - Hertz: the ContactMaterial from hertz_material() makes Simbody's own Hunt-Crossley force between the
//    rig's tip spheres equal to the law, k_h delta^1.5 + c_h delta^1.5 delta', exactly (posed rig, force read
//    from the CompliantContactSubsystem: this checks engines.md's combination rules on this build);
//  - spring-dashpot: the force element is k delta + c delta' (clipped at zero when the law is);
//  - native: steel's plane-strain modulus;
//  - Newton: Simbody's rigid contact reverses the closing speed with the target e at the rig's closing
//    speed (the first impact of the free vibration case, 0.075 m/s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "adapters/common/rig.h"
#include "adapters/simbody/simbody_chain.h"
#include "adapters/simbody/simbody_contact.h"
#include "adapters/simbody/simbody_simulator.h"
#include "engine_measurements.h"
#include "harness/scoring/metrics.h"
#include "reference_fixtures.h"

namespace ib {
namespace simbody_contact_mapping_test {

using namespace simbody;

// Frame 1 turned about its first hinge so that its tip overlaps frame 2's sphere, moving toward it: the
// indentation and its rate from the sphere centres as Simbody places them.
struct Posed {
  double indentation_m = 0, rate_m_s = 0, simbody_force_n = 0;
};

Posed pose_and_read(const RigSpec& rig, const ContactSetup& setup, double overlap_m, double rate_rad_s) {
  SimbodyChain chain(rig);
  SimbodyContact contact(chain, setup, rig);
  SimTK::State state = chain.initial_state();
  const double lever_m = rig.frames[0].tip_z_m - rig.frames[0].bodies.front().joint_z_m;
  for (int j = 0; j < rig.frames[0].chain.links; ++j) chain.set_hinge(state, 0, j, 0, 0);
  chain.set_hinge(state, 0, 0, std::asin((rig.gap_m + overlap_m) / lever_m), rate_rad_s);
  chain.system().realize(state, SimTK::Stage::Velocity);
  const SimTK::Vec3 d = chain.tip_position_m(state, 1) - chain.tip_position_m(state, 0);
  Posed p;
  p.indentation_m = 2 * rig.sphere_radius_m - d.norm();
  p.rate_m_s = -SimTK::dot(chain.tip_velocity_m_s(state, 1) - chain.tip_velocity_m_s(state, 0), d / d.norm());
  p.simbody_force_n = contact.force_n(state);
  return p;
}

TEST(SimbodyContactMapping, HertzMaterialGivesTheLawInClosedForm) {
  const HertzLaw law{2.31e10, 1.5, 3 * 2.31e10 * (1 - 0.64) / (4 * 0.1644)};
  const HuntCrossleyMaterial m = hertz_material(law, kTipSphereRadius_m);
  for (double delta : {1e-7, 1e-6, 2e-5})
    for (double rate : {-0.1, 0.0, 0.2}) {
      const double expected =
          std::max(0.0, law.stiffness * std::pow(delta, 1.5) + law.damping * std::pow(delta, 1.5) * rate);
      EXPECT_NEAR(hunt_crossley_force_n(m, kTipSphereRadius_m, delta, rate) / expected, 1, 1e-12);
    }
}

// Simbody's own Hunt-Crossley force on the posed rig (free vibration case, K = 8) against the law at the
// same indentation and rate: equal to 1e-9 (the law's c_h is the scenario's constant).
TEST(SimbodyContactMapping, SimbodysHuntCrossleyForceIsTheHertzLaw) {
  const Scenario s = testing::paper_scenario("free_vibration");
  const RigSpec rig = build_rig(s, ContactLaw::hertz, default_links(s));
  const HertzLaw law = std::get<HertzLaw>(rig.law);
  const ContactSetup setup = contact_setup(ContactPath::matched, rig.law);
  ASSERT_EQ(setup.kind, ContactKind::hunt_crossley);
  for (double overlap : {2e-6, 2e-5})
    for (double rate_rad_s : {0.0, 0.3, -0.3}) {
      const Posed p = pose_and_read(rig, setup, overlap, rate_rad_s);
      const double law_n = std::max(0.0, law.stiffness * std::pow(p.indentation_m, 1.5) +
                                             law.damping * std::pow(p.indentation_m, 1.5) * p.rate_m_s);
      std::printf("delta %.4g m, delta' %+.4f m/s: Simbody %.6g N, law %.6g N\n", p.indentation_m, p.rate_m_s,
                  p.simbody_force_n, law_n);
      ASSERT_GT(p.indentation_m, 0);
      EXPECT_NEAR(p.simbody_force_n / law_n, 1, 1e-9);
    }
}

TEST(SimbodyContactMapping, SpringDashpotElementIsTheLaw) {
  Scenario s = testing::paper_scenario("free_vibration");
  for (bool clip : {false, true}) {
    s.contact.viscoelastic->clip_tension = clip;
    const RigSpec rig = build_rig(s, ContactLaw::viscoelastic, default_links(s));
    const ViscoelasticLaw law = std::get<ViscoelasticLaw>(rig.law);
    const ContactSetup setup = contact_setup(ContactPath::matched, rig.law);
    ASSERT_EQ(setup.kind, ContactKind::spring_dashpot);
    // -3 rad/s: a separation fast enough that the unclipped law pulls
    for (double rate_rad_s : {0.0, 0.3, -3.0}) {
      const Posed p = pose_and_read(rig, setup, 1e-5, rate_rad_s);
      const double raw = law.stiffness_n_per_m * p.indentation_m + law.damping_n_s_per_m * p.rate_m_s;
      const double expected = clip ? std::max(0.0, raw) : raw;
      EXPECT_NEAR(p.simbody_force_n, expected, 1e-9 * std::abs(raw)) << "clip " << clip << ", rate " << rate_rad_s;
    }
  }
}

TEST(SimbodyContactMapping, NativeIsSteel) {
  const HuntCrossleyMaterial m = steel_material();
  EXPECT_NEAR(m.stiffness_pa, 200e9 / (1 - 0.3 * 0.3), 1e-3);
  EXPECT_EQ(m.dissipation_s_per_m, 0.2);
  const Scenario s = testing::paper_scenario("free_vibration");
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton})
    EXPECT_EQ(contact_setup(ContactPath::native, make_contact_model(s, law)).kind, ContactKind::hunt_crossley);
}

TEST(SimbodyContactMapping, HertzWithAnotherExponentIsInjectedAndSaysSo) {
  const ContactSetup setup = contact_setup(ContactPath::matched, HertzLaw{1e9, 1.0, 0});
  EXPECT_EQ(setup.kind, ContactKind::injected);
  EXPECT_NE(setup.note.find("exponent"), std::string::npos);
}

// Newton: the closing speed reversed with factor e at the impact. The harness reads it at the end of the
// impact step, when the chain's fast modes struck by the impulse have already slowed the separation at
// first order in h: 0.762 at 5e-5 s, 0.792 at 1e-5 s, 0.798 at 2e-6 s (measured); within 0.5 % at 2e-6 s.
TEST(SimbodyContactMapping, RigidNewtonRestitutionAtTheRigsClosingSpeed) {
  std::vector<double> errors;
  for (double h : {1e-5, 2e-6}) {
    auto simulator = make_simbody_simulator();
    const testing::NewtonFirstImpact impact = testing::newton_first_impact(*simulator, h);
    std::printf("newton rigid h = %g s: restitution %.5f at %.4f m/s over %d impact(s)\n", h,
                impact.metrics.mean_restitution, impact.metrics.mean_approach_velocity_m_s, impact.metrics.impacts);
    EXPECT_EQ(impact.metrics.impacts, 1);
    errors.push_back(impact.restitution_error);
  }
  EXPECT_LT(errors[0], 0.02);
  EXPECT_LT(errors[1], 0.005);
  EXPECT_LT(errors[1] * 3, errors[0]);  // first order in h
}

}  // namespace simbody_contact_mapping_test
}  // namespace ib
