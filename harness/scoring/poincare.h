// A forced run read as a vibro-impact engineer reads it: its stroboscopic (Poincare) samples, the
// state once per motor period, and the regime they show (no impact, period-n, irregular).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "model/trajectory.h"

namespace ib {

// The state of both tips at one motor phase 0 (t = k / f_motor: every run starts at phase 0).
struct PoincareSample {
  long long period_index = 0;  // k
  double time_s = 0;
  std::array<double, 2> displacement_m{};
  std::array<double, 2> velocity_m_s{};
};

// Every sample t = k / frequency_hz in [start_s, end_s) that the series covers, interpolated by cubic
// Hermite between the series' samples (displacement with its velocity as slope, velocity with its
// acceleration), so that the error is fourth order in the sample interval, not second.
std::vector<PoincareSample> poincare_samples(const Trajectory& trajectory, double frequency_hz, double start_s,
                                             double end_s);

enum class RegimeKind { no_impact, periodic, irregular };
const char* to_string(RegimeKind kind);

struct Regime {
  RegimeKind kind = RegimeKind::irregular;
  int period = 0;                 // n of period-n (0 unless periodic)
  double impacts_per_period = 0;  // impacts per n motor periods (NaN unless periodic)
  std::string label() const;      // "no impact", "period-2", "irregular"
};

// The size of the motion in a window: each frame's largest |displacement| and |velocity| over the series
// in [start_s, end_s], in the order frame 1 u, v, frame 2 u, v. What "equal" Poincare samples are measured by.
std::array<double, 4> orbit_scale(const Trajectory& trajectory, double start_s, double end_s);

// How close two samples must be to count as the same point of the orbit: their difference in each
// frame's displacement and velocity, relative to the size of that quantity's motion (orbit_scale).
struct RegimeSettings {
  int max_period = 8;                // the longest period looked for [motor periods]
  double relative_tolerance = 0.01;  // [-] (a slowly decaying start-up transient must not read as irregular)
};

// The regime of a window: no impact when none started in it; period-n with the smallest n for which
// every sample equals the one n periods later within the tolerance (impacts per period = impacts x n /
// periods); irregular when no n up to max_period does (or fewer than 2 max_period samples are there to tell).
Regime classify_regime(const std::vector<PoincareSample>& samples, const std::array<double, 4>& scale,
                       int impacts_in_window, double periods_in_window, const RegimeSettings& settings = {});

}  // namespace ib
