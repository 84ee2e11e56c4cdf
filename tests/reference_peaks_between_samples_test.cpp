// The reference's peak columns hold the largest |acceleration| of each output interval, between the samples
// too: in free flight they are found by a scan of the tips' jerk on a sub-grid and located on Taylor
// polynomials, in contact on the dense output. A run sampled densely over the same stretch shows what lies
// between the coarse samples: each coarse interval's peak must be at least the dense samples' largest value
// there and exceed it by no more than dense sampling can miss at the top of a peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "reference_fixtures.h"

namespace ib {
namespace reference_peaks_between_samples_test {

struct Window {
  double start_s, end_s, coarse_rate_hz, dense_rate_hz;
};

// At the dense rate the fastest mode turns by omega h per sample, so a sample misses the top of one of its
// peaks by at most 1 - cos(omega h / 2) ~ (omega h)^2 / 8 of its amplitude; the largest |acceleration| bounds
// every mode's share.
double dense_miss_bound(const ModalModel& model, double dense_rate_hz, double largest_acceleration) {
  const double turn = model.omega_rad_s.maxCoeff() / dense_rate_hz;
  return turn * turn / 8 * largest_acceleration;
}

void expect_peaks_between_samples(const char* scenario, ContactLaw law, const Window& w) {
  const Scenario s = testing::paper_scenario(scenario);
  const ModalModel model = build_modal_model(s, law, ModeSelection{});
  const ModalState x0 = initial_state(s, model);
  const ReferenceSolution coarse = solve_reference(model, x0, w.end_s, {w.start_s, w.end_s, w.coarse_rate_hz}, {});
  ReferenceSettings samples_only;
  samples_only.peaks_between_samples = false;
  const ReferenceSolution dense =
      solve_reference(model, x0, w.end_s, {w.start_s, w.end_s, w.dense_rate_hz}, samples_only);
  ASSERT_EQ(coarse.status, RunStatus::ok) << coarse.reason;
  ASSERT_EQ(dense.status, RunStatus::ok) << dense.reason;
  ASSERT_FALSE(coarse.trajectory.events.empty()) << scenario << ": the stretch should hold impacts";
  const int per_interval = static_cast<int>(std::lround(w.dense_rate_hz / w.coarse_rate_hz));
  const Trajectory& c = coarse.trajectory;
  const Trajectory& d = dense.trajectory;
  ASSERT_EQ(d.size(), (c.size() - 1) * per_interval + 1);
  int found_between = 0;
  for (int f = 0; f < 2; ++f) {
    double largest = 0;
    for (double a : d.acceleration_m_s2[f]) largest = std::max(largest, std::abs(a));
    const double miss = dense_miss_bound(model, w.dense_rate_hz, largest);
    for (std::size_t k = 1; k < c.size(); ++k) {
      double dense_peak = 0;
      // the interval's own samples, the one that opens it included (the recorder's peak starts from it)
      for (std::size_t j = (k - 1) * per_interval; j <= k * per_interval; ++j)
        dense_peak = std::max(dense_peak, std::abs(d.acceleration_m_s2[f][j]));
      ASSERT_NEAR(d.acceleration_m_s2[f][k * per_interval], c.acceleration_m_s2[f][k], 1e-9 * largest)
          << scenario << ", frame " << f + 1 << " at " << c.time_s[k] << " s: the two runs are one motion";
      const double peak = c.peak_abs_acceleration_m_s2[f][k];
      EXPECT_GE(peak, dense_peak - 1e-9 * largest) << scenario << ", frame " << f + 1 << ", interval ending "
                                                   << c.time_s[k] << " s: a peak between the samples was missed";
      EXPECT_LE(peak, dense_peak + miss) << scenario << ", frame " << f + 1 << ", interval ending " << c.time_s[k]
                                         << " s: larger than anything the dense samples approach";
      const double ends = std::max(std::abs(c.acceleration_m_s2[f][k - 1]), std::abs(c.acceleration_m_s2[f][k]));
      found_between += peak > ends * (1 + 1e-3);
    }
  }
  EXPECT_GT(found_between, 10) << scenario << ": the check needs peaks that lie between the coarse samples";
}

// The resonance with Hertz contact after its first impacts: free flight rings in every mode between them.
TEST(ReferencePeaksBetweenSamples, ResonanceHertzPeakColumnsAreTheDenseMaxima) {
  expect_peaks_between_samples("resonance", ContactLaw::hertz, {2.5, 3.0, 256, 65536});
}

// The free vibration released against the other frame, with the spring-dashpot law.
TEST(ReferencePeaksBetweenSamples, FreeVibrationSpringDashpotPeakColumnsAreTheDenseMaxima) {
  expect_peaks_between_samples("free_vibration", ContactLaw::viscoelastic, {0.0, 0.5, 256, 65536});
}

// The free vibration with Newton impacts: each impulse excites every mode, and near the top of a slow peak a fast
// mode's wiggle makes the jerk vanish twice within a sub-interval, one sign at both its ends; the search must
// still find that peak (a dense grid, since the wiggles are microseconds apart).
TEST(ReferencePeaksBetweenSamples, FreeVibrationNewtonPeakColumnsAreTheDenseMaxima) {
  expect_peaks_between_samples("free_vibration", ContactLaw::newton, {0.0, 0.375, 4096, 4096 * 64});
}

}  // namespace reference_peaks_between_samples_test
}  // namespace ib
