// Stroboscopic samples against a closed form, and the regime read from them, just inside and just outside the
// tolerance that tells a repeating orbit from a moving one.
#include "harness/scoring/poincare.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ib {
namespace poincare_test {

// u = A cos(w t + phase) on both frames, sampled at `rate_hz` from 0 to `end_s`, with exact v and a.
Trajectory harmonic(double amplitude_m, double omega_rad_s, double phase_rad, double rate_hz, double end_s) {
  Trajectory t;
  t.output_rate_hz = rate_hz;
  const long long n = static_cast<long long>(std::round(end_s * rate_hz)) + 1;
  for (long long k = 0; k < n; ++k) {
    const double time = static_cast<double>(k) / rate_hz, angle = omega_rad_s * time + phase_rad;
    t.time_s.push_back(time);
    for (int f = 0; f < 2; ++f) {
      const double a = (f + 1) * amplitude_m;
      t.displacement_m[f].push_back(a * std::cos(angle));
      t.velocity_m_s[f].push_back(-a * omega_rad_s * std::sin(angle));
      t.acceleration_m_s2[f].push_back(-a * omega_rad_s * omega_rad_s * std::cos(angle));
    }
  }
  return t;
}

TEST(PoincareSamples, LieOnTheClosedFormOncePerMotorPeriodWithFourthOrderInterpolation) {
  // the response at the motor's frequency (7 Hz) sampled at 4096 Hz: phase 0 of the motor falls between samples
  const double f_hz = 7.0, w = 2 * M_PI * f_hz, amplitude_m = 1e-3, phase = 0.3;
  const Trajectory t = harmonic(amplitude_m, w, phase, 4096, 3.0);
  const auto samples = poincare_samples(t, f_hz, 1.0, 3.0);
  ASSERT_EQ(samples.size(), 14u);  // k = 7 .. 20: t = 1 s included, 3 s (the end) not
  for (const PoincareSample& p : samples) {
    EXPECT_NEAR(p.time_s, p.period_index / f_hz, 1e-15);
    // at every motor phase 0 the state is the same: A cos(phase), -A w sin(phase)
    EXPECT_NEAR(p.displacement_m[0], amplitude_m * std::cos(phase), 1e-12);  // linear interpolation: 1.4e-8 off
    EXPECT_NEAR(p.velocity_m_s[0], -amplitude_m * w * std::sin(phase), 1e-10);
    EXPECT_NEAR(p.displacement_m[1], 2 * amplitude_m * std::cos(phase), 2e-12);
  }
}

TEST(PoincareSamples, NoneOutsideTheSeries) {
  const Trajectory t = harmonic(1e-3, 10, 0, 1000, 1.0);
  EXPECT_TRUE(poincare_samples(t, 7.0, 2.0, 3.0).empty());
  EXPECT_TRUE(poincare_samples(Trajectory{}, 7.0, 0.0, 1.0).empty());
}

// Samples that repeat every `period` motor periods, with a relative disturbance `noise` of the orbit's scale.
std::vector<PoincareSample> orbit(int period, int count, double noise) {
  std::vector<PoincareSample> samples;
  for (int k = 0; k < count; ++k) {
    PoincareSample p;
    p.period_index = k;
    const double level = 1e-3 * (1 + (k % period)) / period;
    const double wobble = noise * std::sin(1.7 * k);
    p.displacement_m = {level + 1e-3 * wobble, -0.5 * level};
    p.velocity_m_s = {0.05 * level / 1e-3 + 0.05 * wobble, 0.01};
    samples.push_back(p);
  }
  return samples;
}
const std::array<double, 4> kScale = {1e-3, 0.05, 5e-4, 0.01};

TEST(Regime, PeriodTwoWithOneImpactPerTwoPeriodsIsReadAsSuch) {
  const Regime r = classify_regime(orbit(2, 40, 0), kScale, 20, 40);
  EXPECT_EQ(r.kind, RegimeKind::periodic);
  EXPECT_EQ(r.period, 2);
  EXPECT_DOUBLE_EQ(r.impacts_per_period, 1.0);
  EXPECT_EQ(r.label(), "period-2");
}

TEST(Regime, NoiseBelowTheToleranceKeepsThePeriodAndAboveItMakesItIrregular) {
  EXPECT_EQ(classify_regime(orbit(3, 40, 0.004), kScale, 40, 40).period, 3);  // +-0.4 %: within 1 %
  const Regime noisy = classify_regime(orbit(3, 40, 0.02), kScale, 40, 40);   // +-2 %
  EXPECT_EQ(noisy.kind, RegimeKind::irregular);
  EXPECT_EQ(noisy.label(), "irregular");
  EXPECT_TRUE(std::isnan(noisy.impacts_per_period));
}

TEST(Regime, NoImpactWhateverTheSamplesAndTooFewSamplesAreIrregular) {
  EXPECT_EQ(classify_regime(orbit(1, 40, 0), kScale, 0, 40).label(), "no impact");
  EXPECT_EQ(classify_regime(orbit(1, 10, 0), kScale, 10, 10).kind, RegimeKind::irregular);  // < 2 x 8 samples
  EXPECT_EQ(classify_regime(orbit(1, 16, 0), kScale, 16, 16).period, 1);
}

// ---- the tolerance's edge -------------------------------------------------------------------------------

// A sweep labels each ratio's regime with the default settings (sweep_row.cpp), whose tolerance poincare.h
// documents as 1 % of each quantity's orbit scale: written out here rather than read from RegimeSettings, so
// that a changed default is a failing test, not a silently moved edge.
constexpr double kDocumentedRelativeTolerance = 0.01;

// The scale of each coordinate (frame 1 u, v, frame 2 u, v), powers of two, so that the tolerance's absolute
// size, 0.01 x scale, is the same double here as in the classifier.
const std::array<double, 4> kPowerOfTwoScale = {0x1p-10, 0x1p-4, 0x1p-11, 0x1p-6};

// A settled orbit whose samples alternate: the even ones at the resting state below, the odd ones moved by
// `offset` in coordinate `coordinate` alone. That coordinate is 0 on the even samples (the tip at its rest
// position, or at a turning point, at motor phase 0), so the difference the classifier sees is `offset` exactly.
// Within the tolerance the orbit is one point, period-1; beyond it the samples repeat only every two periods.
std::vector<PoincareSample> alternating_orbit(int coordinate, double offset) {
  std::vector<PoincareSample> samples;
  for (int k = 0; k < 24; ++k) {  // 3 x max_period: enough to tell period 1 and 2 apart
    std::array<double, 4> state = {0.3e-3, -0.02, 0.1e-3, 0.004};
    state[coordinate] = k % 2 == 0 ? 0.0 : offset;
    PoincareSample p;
    p.period_index = k;
    p.displacement_m = {state[0], state[2]};
    p.velocity_m_s = {state[1], state[3]};
    samples.push_back(p);
  }
  return samples;
}

// One impact per motor period over the 24 periods: period-1 has 1 impact per period, period-2 has 2.
Regime regime_of(const std::vector<PoincareSample>& samples) {
  return classify_regime(samples, kPowerOfTwoScale, 24, 24.0);
}

// A deviation a millionth inside the tolerance, or exactly on it ("within the tolerance": the edge is inside),
// leaves the orbit period-1; a millionth beyond it makes it period-2. In each of the four coordinates, each
// measured against its own scale.
TEST(Regime, ADeviationJustInsideTheToleranceIsPeriodOneAndJustOutsideIsPeriodTwo) {
  const double eps = 1e-6;
  for (int j = 0; j < 4; ++j) {
    const double edge = kDocumentedRelativeTolerance * kPowerOfTwoScale[j];
    SCOPED_TRACE("coordinate " + std::to_string(j) + " (frame 1 u, v, frame 2 u, v)");
    const Regime inside = regime_of(alternating_orbit(j, edge * (1 - eps)));
    EXPECT_EQ(inside.label(), "period-1");
    EXPECT_DOUBLE_EQ(inside.impacts_per_period, 1.0);
    EXPECT_EQ(regime_of(alternating_orbit(j, edge)).label(), "period-1");
    const Regime outside = regime_of(alternating_orbit(j, edge * (1 + eps)));
    EXPECT_EQ(outside.label(), "period-2");
    EXPECT_DOUBLE_EQ(outside.impacts_per_period, 2.0);
    // the same deviation the other way round (the odd samples below the even ones)
    EXPECT_EQ(regime_of(alternating_orbit(j, -edge * (1 - eps))).label(), "period-1");
    EXPECT_EQ(regime_of(alternating_orbit(j, -edge * (1 + eps))).label(), "period-2");
  }
}

}  // namespace poincare_test
}  // namespace ib
