// Energy balance of the reference over runs with many impacts: motor work = change of mechanical
// energy + structural dissipation + contact dissipation, each term computed on its own (free-flight
// integrals in closed form, contact phases by the integrator, Newton losses from the impulse map).
#include <gtest/gtest.h>

#include <cmath>

#include "reference_fixtures.h"

namespace ib {
namespace energy_balance_test {

using testing::paper_scenario;

struct Case {
  const char* scenario;
  ContactLaw law;
  ModeSet modes;
  bool full_length = false;  // the scenario's whole duration (100 s) instead of 20 s
};

class EnergyBalance : public ::testing::TestWithParam<Case> {};

TEST_P(EnergyBalance, MotorWorkEqualsEnergyChangePlusDissipation) {
  const Case c = GetParam();
  Scenario s = paper_scenario(c.scenario);
  if (!c.full_length) s.duration_s = std::min(s.duration_s, 20.0);
  ReferenceSettings settings;
  settings.modes.set = c.modes;
  settings.modes.chain_links = 8;
  const ModalModel model = build_modal_model(s, c.law, settings.modes);
  const ReferenceSolution r =
      solve_reference(model, initial_state(s, model), s.duration_s, {s.duration_s, s.duration_s, 1}, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  EXPECT_GE(r.impacts, 5);
  const EnergyLedger& e = r.energy;
  EXPECT_GT(e.contact_dissipation_j, 0.0);
  EXPECT_GT(e.structural_dissipation_j, 0.0);
  EXPECT_LT(e.relative_residual(), 1e-6) << "work " << e.motor_work_j << " J, dE "
                                         << e.final_energy_j - e.initial_energy_j << " J, structural "
                                         << e.structural_dissipation_j << " J, contact " << e.contact_dissipation_j
                                         << " J";
}

INSTANTIATE_TEST_SUITE_P(Reference, EnergyBalance,
                         ::testing::Values(Case{"resonance", ContactLaw::hertz, ModeSet::beam, true},
                                           Case{"resonance", ContactLaw::viscoelastic, ModeSet::beam},
                                           Case{"resonance", ContactLaw::newton, ModeSet::beam},
                                           Case{"pre_resonance", ContactLaw::hertz, ModeSet::beam},
                                           Case{"free_vibration", ContactLaw::hertz, ModeSet::beam},
                                           Case{"free_vibration", ContactLaw::viscoelastic, ModeSet::beam},
                                           Case{"resonance", ContactLaw::hertz, ModeSet::chain},
                                           Case{"resonance", ContactLaw::newton, ModeSet::chain}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.scenario) + "_" + to_string(info.param.law) + "_" +
                                  to_string(info.param.modes);
                         });

}  // namespace energy_balance_test
}  // namespace ib
