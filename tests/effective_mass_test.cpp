// The effective mass of the tips at contact, from independent derivations: a one-link chain by hand (a
// rigid bar hinged at its base, I_hinge / r^2), and the combined mass of the two tips against 1/|b|^2 of
// the chain's modal model (the reference's code, not the rig's). A 5 % error in either fails here; the
// Newton impulse of every engine's injected contact (newton_restitution_test.cpp) is (1 + e) times it.
#include "adapters/common/rig.h"

#include <gtest/gtest.h>

#include <cmath>

#include "physics/link_chain.h"
#include "physics/modal_model.h"
#include "reference_fixtures.h"

namespace ib {
namespace effective_mass_test {

// A rigid link hinged at z0 carrying the tip mass at L: the mass that a force at the tip, along the
// motion, meets is I_hinge / (L - z0)^2, with I_hinge = I_c + m (c - z0)^2 + M (L - z0)^2.
double one_link_tip_mass_by_hand(const FrameSpec& frame) {
  const LinkChain chain = build_link_chain(frame, 1);
  const ChainBody& link = chain.bodies.front();
  const double arm = frame.length_m - link.start_m;
  const double hinge_inertia =
      link.inertia_kg_m2 + link.mass_kg * std::pow(link.center_m - link.start_m, 2) + frame.tip_mass_kg * arm * arm;
  return hinge_inertia / (arm * arm);
}

TEST(EffectiveMass, OneLinkChainIsTheHingedBarByHand) {
  const Scenario s = testing::paper_scenario("resonance");
  const RigSpec rig = build_rig(s, ContactLaw::newton, 1);
  double inverse = 0;
  for (int f = 0; f < 2; ++f) {
    const double by_hand = one_link_tip_mass_by_hand(s.frames[f]);
    EXPECT_NEAR(rig.frames[f].tip_effective_mass_kg / by_hand, 1, 1e-12) << "frame " << f + 1;
    inverse += 1 / by_hand;
  }
  EXPECT_NEAR(rig.contact_effective_mass_kg * inverse, 1, 1e-12);  // 1 / (1/m1 + 1/m2)
}

TEST(EffectiveMass, TheTwoTipsCombineAsTheChainsModalModelSays) {
  for (const char* name : {"resonance", "free_vibration"})
    for (int links : {2, 8, 16}) {
      const Scenario s = testing::paper_scenario(name);
      const RigSpec rig = build_rig(s, ContactLaw::newton, links);
      ModeSelection chain;
      chain.set = ModeSet::chain;
      chain.chain_links = links;
      const ModalModel model = build_modal_model(s, ContactLaw::newton, chain);
      EXPECT_NEAR(rig.contact_effective_mass_kg / model.contact_effective_mass_kg(), 1, 1e-9) << name << ", " << links;
      // each frame alone: 1 / sum over its modes of phi_n(L)^2
      for (int f = 0; f < 2; ++f)
        EXPECT_NEAR(rig.frames[f].tip_effective_mass_kg * model.frames[f].tip.squaredNorm(), 1, 1e-9)
            << name << ", " << links;
    }
}

}  // namespace effective_mass_test
}  // namespace ib
