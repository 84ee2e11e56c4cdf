// The extreme scenario of 1000 s without damping (scenarios/extreme/zero_damping_1000s.toml) on the
// reference: total mechanical energy is conserved over thousands of impacts. A test of its own, built in the
// optimized build only (tests/CMakeLists.txt): under the sanitizers its 1000 s would run the reference's code
// that the shorter reference tests run too, twenty times slower.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "reference_fixtures.h"

namespace ib {
namespace zero_damping_energy_test {

// No structural damping, no motor, elastic contact: the total mechanical energy (kinetic + strain +
// elastic contact energy) after 1000 s and thousands of impacts equals the initial strain energy of
// frame 1's static tip-load shape, (1/2) (3 EI / L^3) u0^2. Bounds: the Newton law's impulse map is
// exact (1e-10); the compliant laws' contacts are integrated at rtol 1e-9, and their drift is about 1e-6
// (Hertz) and 1e-7 (spring-dashpot) of the energy; the bound 1e-5 leaves room and still fails on a
// contact that loses or gains 1e-8 of the energy per impact.
TEST(ZeroDamping1000s, TotalEnergyIsConserved) {
  const Scenario s = load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/extreme/zero_damping_1000s.toml");
  ASSERT_EQ(s.duration_s, 1000.0);
  ASSERT_FALSE(s.motor.has_value());
  for (const FrameSpec& f : s.frames) ASSERT_EQ(f.damping_ratio, 0.0);
  const FrameSpec& f1 = s.frames[0];
  const double u0 = s.initial.frame1_tip_displacement_m;
  const double strain_energy = 0.5 * 3 * f1.bending_stiffness_n_m2() / std::pow(f1.length_m, 3) * u0 * u0;
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
    const ModalModel model = build_modal_model(s, law, ReferenceSettings{}.modes);
    const ReferenceSolution solution = solve_reference(model, initial_state(s, model), s.duration_s,
                                                       {s.duration_s, s.duration_s, 1}, ReferenceSettings{});
    ASSERT_EQ(solution.status, RunStatus::ok) << to_string(law) << ": " << solution.reason;
    const EnergyLedger& e = solution.energy;
    EXPECT_GT(solution.impacts, 1000) << to_string(law);
    EXPECT_NEAR(e.initial_energy_j / strain_energy, 1.0, 1e-4) << to_string(law);  // 10 modes of the static shape
    EXPECT_EQ(e.motor_work_j, 0.0) << to_string(law);
    EXPECT_EQ(e.structural_dissipation_j, 0.0) << to_string(law);
    const double drift = (e.final_energy_j - e.initial_energy_j) / e.initial_energy_j;
    std::printf("%s: %lld impacts, energy drift over 1000 s %.3g\n", to_string(law), solution.impacts, drift);
    EXPECT_LT(std::abs(drift), law == ContactLaw::newton ? 1e-10 : 1e-5) << to_string(law);
  }
}

}  // namespace zero_damping_energy_test
}  // namespace ib
