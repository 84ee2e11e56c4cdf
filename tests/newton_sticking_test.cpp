// The Newton law's accumulation of impacts: detected, switched to a sticking phase that holds
// delta = 0 with the constraint force, released when that force would turn tensile, never an endless loop.
#include <gtest/gtest.h>

#include <cmath>

#include "reference_fixtures.h"

namespace ib {
namespace newton_sticking_test {

using testing::paper_scenario;

// A tip mass on a spring released toward a rigid wall that stands on the near side of its rest
// position: the spring presses it against the wall, so with e < 1 the bounces accumulate at a time
// known in closed form, and then it rests on the wall with the spring force m omega^2 |d|.
TEST(NewtonSticking, BouncesAccumulateAtTheClosedFormTimeThenStick) {
  const double mass = 0.64439, omega = 2 * M_PI * 7, amplitude = 2e-3, wall = -0.5e-3, e = 0.5;
  ModalModel model;
  model.frames[0].omega_rad_s = Eigen::VectorXd::Constant(1, omega);
  model.frames[0].zeta = Eigen::VectorXd::Zero(1);
  model.frames[0].tip = Eigen::VectorXd::Constant(1, 1 / std::sqrt(mass));
  model.frames[1].omega_rad_s = model.frames[1].zeta = model.frames[1].tip = Eigen::VectorXd(0);  // rigid
  model.gap_m = wall;
  model.contact = NewtonLaw{e};
  model.finalise();
  ModalState x{Eigen::VectorXd::Constant(1, -amplitude * std::sqrt(mass)), Eigen::VectorXd::Zero(1)};

  // u = -A cos(omega t) reaches the wall at t1 with speed v1; after a rebound at v the tip returns to
  // the wall after (2/omega) atan(v / (omega |d|)) at the same speed.
  const double t1 = std::acos(-wall / amplitude) / omega, v1 = amplitude * omega * std::sin(omega * t1);
  double accumulation = t1, v = v1;
  int bounces_before_rest = 0;
  for (int k = 1; k < 200; ++k) {
    v *= e;
    accumulation += 2 / omega * std::atan(v / (omega * -wall));
    if (v > 1e-4) ++bounces_before_rest;
  }
  ReferenceSettings settings;
  const double duration = accumulation + 0.1;
  const ReferenceSolution r = solve_reference(model, x, duration, {0, duration, 10000}, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  EXPECT_EQ(r.sticking_phases, 1);
  const ContactEvent& rest = r.trajectory.events.back();
  EXPECT_NEAR(rest.onset_time_s, accumulation, 2 * settings.accumulation_time_s);
  EXPECT_NEAR(rest.end_time_s, duration, 1e-12);  // the spring keeps it pressed until the run ends
  EXPECT_GT(static_cast<int>(r.trajectory.events.size()), bounces_before_rest);
  EXPECT_NEAR(r.trajectory.events.front().onset_time_s, t1, 1e-12);
  EXPECT_NEAR(r.trajectory.events.front().approach_velocity_m_s, v1, 1e-12);
  // resting on the wall: the contact force is the spring force and the tip stays at the wall
  const double spring_force = mass * omega * omega * -wall;
  const Trajectory& t = r.trajectory;
  int resting_samples = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t.time_s[k] <= rest.onset_time_s) continue;
    ++resting_samples;
    EXPECT_NEAR(t.contact_force_n[k] / spring_force, 1.0, 1e-9);
    EXPECT_NEAR(t.displacement_m[0][k], wall, 1e-12);
  }
  EXPECT_GT(resting_samples, 900);
  EXPECT_LT(r.energy.relative_residual(), 1e-6);
}

// The rig with perfectly plastic impacts: the frames stick and are pulled apart again as the motor
// turns; every sticking phase is released, the force never pulls, and energy balances.
TEST(NewtonSticking, PlasticImpactsStickAndReleaseOnTheRig) {
  Scenario s = paper_scenario("resonance");
  s.duration_s = 20;
  s.contact.newton->restitution = 0;
  ReferenceSettings settings;
  const ModalModel model = build_modal_model(s, ContactLaw::newton, settings.modes);
  const ReferenceSolution r =
      solve_reference(model, initial_state(s, model), s.duration_s, {0, s.duration_s, 4096}, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  EXPECT_GT(r.sticking_phases, 5);
  for (const ContactEvent& e : r.trajectory.events) {
    EXPECT_GE(e.end_time_s, e.onset_time_s);
    EXPECT_NEAR(e.rebound_velocity_m_s, 0.0, 1e-9);
  }
  double largest = 0;
  for (double f : r.trajectory.contact_force_n) largest = std::max(largest, f);
  EXPECT_GT(largest, 0.0);
  for (double f : r.trajectory.contact_force_n) EXPECT_GE(f, -1e-9 * largest);
  EXPECT_LT(r.energy.relative_residual(), 1e-6);
}

}  // namespace newton_sticking_test
}  // namespace ib
