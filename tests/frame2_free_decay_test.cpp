// Frame 2 on its own: released in its first mode with frame 1 at rest (the tips never touch), the
// reference's frame 2 rings at its own first frequency and decays with the scenario's damping ratio
// (0.003), measured from its tip's peaks. Frame 1's decay is checked everywhere else; a mistake in frame
// 2's damping or mass (the second frame's parameters read or stacked wrongly) shows here alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/beam_modes.h"
#include "physics/modal_model.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace frame2_free_decay_test {

// Frequency and damping ratio from frame 2's positive tip peaks (parabola-refined), as engine_measurements.h
// measures frame 1's.
std::pair<double, double> frame2_decay(const Trajectory& t) {
  const std::vector<double>& u = t.displacement_m[1];
  const double dt = 1 / t.output_rate_hz;
  std::vector<double> times, logs;
  for (std::size_t k = 1; k + 1 < u.size(); ++k) {
    if (!(u[k] > 0 && u[k] > u[k - 1] && u[k] >= u[k + 1])) continue;
    const double a = u[k - 1], b = u[k], c = u[k + 1], shift = 0.5 * (a - c) / (a - 2 * b + c);
    times.push_back(t.time_s[k] + shift * dt);
    logs.push_back(std::log(b - 0.25 * (a - c) * shift));
  }
  const double n = static_cast<double>(times.size());
  const double frequency_hz = (n - 1) / (times.back() - times.front());
  double mt = 0, ml = 0, sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < times.size(); ++i) mt += times[i] / n, ml += logs[i] / n;
  for (std::size_t i = 0; i < times.size(); ++i)
    sxy += (times[i] - mt) * (logs[i] - ml), sxx += (times[i] - mt) * (times[i] - mt);
  const double ratio = (-sxy / sxx) / (2 * M_PI * frequency_hz);
  return {frequency_hz, ratio / std::sqrt(1 + ratio * ratio)};
}

TEST(Frame2FreeDecay, RingsAtItsOwnFrequencyWithTheScenariosDamping) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 20;  // about 160 periods of frame 2 (8.6 Hz)
  s.scoring_window_s = 20;
  s.initial.frame1_tip_displacement_m = 0;
  auto reference = make_reference_simulator();
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.output_rate_hz = 4096;
  settings.series_start_s = 0;
  // the saved-state layout of this run: its modal q then v, frame 2's first mode displaced so that its tip
  // swings +-0.5 mm (a 1 mm gap: no contact)
  const ModalModel model = build_modal_model(s, ContactLaw::viscoelastic, ModeSelection{});
  const int n = model.mode_count(), first_of_frame2 = model.frame_mode_count(0);
  RunSettings probe = settings;
  Scenario short_run = s;
  short_run.duration_s = short_run.scoring_window_s = 0.01;
  SavedState start = *reference->run(short_run, probe).final_state;
  std::fill(start.values.begin(), start.values.end(), 0.0);
  start.values[first_of_frame2] = 0.5e-3 / model.frames[1].tip[0];
  ASSERT_EQ(static_cast<int>(start.values.size()), 2 * n);
  settings.initial_state = start;
  const RunResult run = reference->run(s, settings);
  ASSERT_EQ(run.status, RunStatus::ok) << run.reason;
  ASSERT_TRUE(run.trajectory.events.empty()) << "the tips touched";
  const auto [frequency_hz, damping_ratio] = frame2_decay(run.trajectory);
  // the scenario's number, written out: every mode of frame 2 has zeta = 0.003
  EXPECT_NEAR(damping_ratio / 0.003, 1, 0.01) << damping_ratio;
  // frame 2's first frequency, a cantilever with its own (lighter) tip mass: higher than frame 1's 6.95 Hz
  const double expected_hz = CantileverModes(s.frames[1], 1).omega_rad_s(0) / (2 * M_PI) * std::sqrt(1 - 0.003 * 0.003);
  EXPECT_NEAR(frequency_hz / expected_hz, 1, 1e-3) << frequency_hz;
  // the Rayleigh estimate of a cantilever with a tip mass (k = 3EI/L^3, mass M + 33/140 m) within 1 %
  const FrameSpec& f = s.frames[1];
  const double inertia = f.columns * f.column_width_m * std::pow(f.column_thickness_m, 3) / 12;
  const double rayleigh_hz = std::sqrt(3 * f.youngs_modulus_pa * inertia / std::pow(f.length_m, 3) /
                                       (f.tip_mass_kg + 33.0 / 140.0 * f.beam_mass_kg())) /
                             (2 * M_PI);
  EXPECT_NEAR(frequency_hz / rayleigh_hz, 1, 0.01) << frequency_hz << " Hz, Rayleigh " << rayleigh_hz << " Hz";
}

}  // namespace frame2_free_decay_test
}  // namespace ib
