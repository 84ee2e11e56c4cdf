// The reference converges: tightening the tolerance changes impact times and peaks less and less,
// more modes change a single impact less and less, and the same input gives the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reference_fixtures.h"

namespace ib {
namespace reference_convergence_test {

using testing::paper_scenario;

ReferenceSolution run(const Scenario& s, ContactLaw law, const ReferenceSettings& settings) {
  const ModalModel model = build_modal_model(s, law, settings.modes);
  return solve_reference(model, initial_state(s, model), s.duration_s, {0, s.duration_s, 4096}, settings);
}

// Largest difference over the first `count` impacts: onset time [s] and relative peak force.
std::pair<double, double> difference(const ReferenceSolution& a, const ReferenceSolution& b, std::size_t count) {
  double time = 0, force = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const ContactEvent &x = a.trajectory.events.at(i), &y = b.trajectory.events.at(i);
    time = std::max(time, std::abs(x.onset_time_s - y.onset_time_s));
    force = std::max(force, std::abs(x.peak_force_n / y.peak_force_n - 1));
  }
  return {time, force};
}

TEST(ReferenceConvergence, TighterToleranceChangesImpactsLessAndLess) {
  // The resonance case is chaotic over tens of seconds (rounding differences grow ~100x per 8 s),
  // so convergence is measured over the first impacts of the free vibration and 3 s of resonance.
  for (const char* name : {"free_vibration", "resonance"}) {
    Scenario s = paper_scenario(name);
    s.duration_s = std::min(s.duration_s, 3.0);
    for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic}) {
      ReferenceSettings settings;
      settings.relative_tolerance = 1e-12;
      settings.absolute_tolerance = 1e-16;
      const ReferenceSolution truth = run(s, law, settings);
      const std::size_t count = std::min<std::size_t>(truth.trajectory.events.size(), 8);
      ASSERT_GE(count, 3u) << name;
      double previous_time = 1, previous_force = 1;
      for (double rtol : {1e-5, 1e-7, 1e-9}) {
        settings.relative_tolerance = rtol;
        settings.absolute_tolerance = rtol * 1e-3;
        const ReferenceSolution r = run(s, law, settings);
        ASSERT_GE(r.trajectory.events.size(), count);
        const auto [time, force] = difference(r, truth, count);
        EXPECT_LE(time, previous_time) << name << " " << to_string(law) << " rtol " << rtol;
        EXPECT_LE(force, previous_force) << name << " " << to_string(law) << " rtol " << rtol;
        previous_time = time;
        previous_force = force;
      }
      EXPECT_LT(previous_time, 1e-8) << name << " " << to_string(law);  // at rtol 1e-9
      EXPECT_LT(previous_force, 1e-6) << name << " " << to_string(law);
    }
  }
}

// The first impact of the free vibration as the mode count grows: its duration and peak force settle.
TEST(ReferenceConvergence, MoreModesChangeAnImpactLessAndLess) {
  Scenario s = paper_scenario("free_vibration");
  s.duration_s = 0.2;
  std::vector<ContactEvent> first;
  for (int n : {5, 10, 20, 40}) {
    ReferenceSettings settings;
    settings.modes.modes_per_frame = n;
    const ReferenceSolution r = run(s, ContactLaw::hertz, settings);
    ASSERT_FALSE(r.trajectory.events.empty());
    first.push_back(r.trajectory.events[0]);
  }
  auto duration = [](const ContactEvent& e) { return e.end_time_s - e.onset_time_s; };
  for (std::size_t i = 1; i + 1 < first.size(); ++i) {
    EXPECT_LT(std::abs(duration(first[i + 1]) - duration(first[i])),
              std::abs(duration(first[i]) - duration(first[i - 1])));
    EXPECT_LT(std::abs(first[i + 1].peak_force_n - first[i].peak_force_n),
              std::abs(first[i].peak_force_n - first[i - 1].peak_force_n));
  }
  EXPECT_LT(std::abs(duration(first[3]) / duration(first[2]) - 1), 2e-3);  // 20 and 40 modes agree
}

TEST(ReferenceConvergence, SameInputGivesTheSameBits) {
  Scenario s = paper_scenario("resonance");
  s.duration_s = 5;
  const ReferenceSolution a = run(s, ContactLaw::hertz, {}), b = run(s, ContactLaw::hertz, {});
  ASSERT_FALSE(a.trajectory.events.empty());
  EXPECT_EQ(a.trajectory.displacement_m[0], b.trajectory.displacement_m[0]);
  EXPECT_EQ(a.trajectory.acceleration_m_s2[1], b.trajectory.acceleration_m_s2[1]);
  EXPECT_EQ(a.trajectory.peak_abs_acceleration_m_s2[0], b.trajectory.peak_abs_acceleration_m_s2[0]);
  ASSERT_EQ(a.trajectory.events.size(), b.trajectory.events.size());
  for (std::size_t i = 0; i < a.trajectory.events.size(); ++i) {
    EXPECT_EQ(a.trajectory.events[i].onset_time_s, b.trajectory.events[i].onset_time_s);
    EXPECT_EQ(a.trajectory.events[i].peak_force_n, b.trajectory.events[i].peak_force_n);
  }
}

}  // namespace reference_convergence_test
}  // namespace ib
