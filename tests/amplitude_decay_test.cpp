// The free decay's logarithmic decrement (harness/scoring/amplitude_decay.h) against its closed form, and the
// cases it must refuse: too few cycles, higher modes riding on the first.
#include "harness/scoring/amplitude_decay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ib {
namespace amplitude_decay_test {

struct Series {
  std::vector<double> time_s, displacement_m;
};

// u = A e^(-zeta omega t) sin(omega_d t) (+ a small higher mode), sampled at rate_hz over [0, end_s].
Series damped_sine(double zeta, double frequency_hz, double end_s, double rate_hz, double higher_mode_m = 0) {
  Series s;
  const double omega = 2 * M_PI * frequency_hz, omega_d = omega * std::sqrt(1 - zeta * zeta);
  for (int k = 0; k / rate_hz <= end_s; ++k) {
    const double t = k / rate_hz;
    s.time_s.push_back(t);
    s.displacement_m.push_back(1e-3 * std::exp(-zeta * omega * t) * std::sin(omega_d * t) +
                               higher_mode_m * std::sin(2 * M_PI * 9.3 * frequency_hz * t));
  }
  return s;
}

TEST(AmplitudeDecay, LogDecrementOfADampedSineIsItsClosedForm) {
  for (double zeta : {0.002, 0.01, 0.05}) {
    const Series s = damped_sine(zeta, 7.0, 3.0, 4096);
    const double expected = 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta);
    // the sampled peak misses the true one by at most half a sample's phase: 1e-3 relative here
    EXPECT_NEAR(log_decrement(s.time_s, s.displacement_m, 0, 3), expected, 2e-3 * expected) << "zeta " << zeta;
  }
}

TEST(AmplitudeDecay, AHigherModeRidingOnTheFirstAddsNoPeaks) {
  const double zeta = 0.01, expected = 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta);
  const Series s = damped_sine(zeta, 7.0, 3.0, 4096, 5e-6);  // 0.5 % of the first mode's initial amplitude
  EXPECT_NEAR(log_decrement(s.time_s, s.displacement_m, 0, 3), expected, 0.05 * expected);
}

TEST(AmplitudeDecay, OnlyTheWindowCounts) {
  const double zeta = 0.01, expected = 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta);
  Series s = damped_sine(zeta, 7.0, 3.0, 4096);
  for (std::size_t k = 0; k < s.time_s.size(); ++k)
    if (s.time_s[k] < 1.0) s.displacement_m[k] *= 3;  // a different decay before the window
  EXPECT_NEAR(log_decrement(s.time_s, s.displacement_m, 1.0, 3.0), expected, 2e-3 * expected);
}

TEST(AmplitudeDecay, FewerThanThreeWholeCyclesGiveNoDecrement) {
  const Series s = damped_sine(0.01, 7.0, 3.0, 4096);
  EXPECT_TRUE(std::isnan(log_decrement(s.time_s, s.displacement_m, 0, 0.40)));  // 2.8 cycles: 2 whole ones
  EXPECT_FALSE(std::isnan(log_decrement(s.time_s, s.displacement_m, 0, 0.60)));
  const std::vector<double> at_rest(s.time_s.size(), 0.0);
  EXPECT_TRUE(std::isnan(log_decrement(s.time_s, at_rest, 0, 3)));
}

}  // namespace amplitude_decay_test
}  // namespace ib
