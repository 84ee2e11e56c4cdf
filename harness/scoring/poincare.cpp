#include "harness/scoring/poincare.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ib {

namespace {

// Cubic Hermite between (y0, slope0) at 0 and (y1, slope1) at h, at s = t / h.
double hermite(double y0, double slope0, double y1, double slope1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * slope0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * h * slope1;
}

}  // namespace

const char* to_string(RegimeKind kind) {
  switch (kind) {
    case RegimeKind::no_impact:
      return "no impact";
    case RegimeKind::periodic:
      return "periodic";
    case RegimeKind::irregular:
      return "irregular";
  }
  return "?";
}

std::string Regime::label() const {
  if (kind == RegimeKind::periodic) return "period-" + std::to_string(period);
  return to_string(kind);
}

std::vector<PoincareSample> poincare_samples(const Trajectory& trajectory, double frequency_hz, double start_s,
                                             double end_s) {
  std::vector<PoincareSample> samples;
  const std::size_t n = trajectory.size();
  if (n < 2 || !(frequency_hz > 0) || trajectory.output_rate_hz <= 0) return samples;
  const double first_s = std::max(start_s, trajectory.time_s.front());
  const double last_s = std::min(end_s, trajectory.time_s.back());
  // k from the first phase 0 at or after first_s; the small margin keeps a sample that lands on first_s
  for (long long k = static_cast<long long>(std::ceil(first_s * frequency_hz - 1e-9));; ++k) {
    const double t = static_cast<double>(k) / frequency_hz;
    if (t >= end_s - 1e-12 || t > last_s) break;
    // the series interval [t_i, t_i+1] that holds t
    const double position = (t - trajectory.time_s.front()) * trajectory.output_rate_hz;
    std::size_t i = static_cast<std::size_t>(std::clamp(std::floor(position), 0.0, static_cast<double>(n - 2)));
    while (i + 2 < n && trajectory.time_s[i + 1] < t) ++i;
    while (i > 0 && trajectory.time_s[i] > t) --i;
    const double h = trajectory.time_s[i + 1] - trajectory.time_s[i];
    const double s = h > 0 ? (t - trajectory.time_s[i]) / h : 0;
    PoincareSample sample;
    sample.period_index = k;
    sample.time_s = t;
    for (int f = 0; f < 2; ++f) {
      const auto& u = trajectory.displacement_m[f];
      const auto& v = trajectory.velocity_m_s[f];
      const auto& a = trajectory.acceleration_m_s2[f];
      sample.displacement_m[f] = hermite(u[i], v[i], u[i + 1], v[i + 1], h, s);
      // an impact inside the interval breaks the velocity's smoothness: fall back to linear there
      const bool smooth = a.size() == n && std::isfinite(a[i]) && std::isfinite(a[i + 1]);
      sample.velocity_m_s[f] = smooth ? hermite(v[i], a[i], v[i + 1], a[i + 1], h, s) : v[i] + s * (v[i + 1] - v[i]);
    }
    samples.push_back(sample);
  }
  return samples;
}

std::array<double, 4> orbit_scale(const Trajectory& trajectory, double start_s, double end_s) {
  std::array<double, 4> scale{};
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (trajectory.time_s[i] < start_s || trajectory.time_s[i] > end_s) continue;
    for (int f = 0; f < 2; ++f) {
      scale[2 * f] = std::max(scale[2 * f], std::abs(trajectory.displacement_m[f][i]));
      scale[2 * f + 1] = std::max(scale[2 * f + 1], std::abs(trajectory.velocity_m_s[f][i]));
    }
  }
  return scale;
}

Regime classify_regime(const std::vector<PoincareSample>& samples, const std::array<double, 4>& scale,
                       int impacts_in_window, double periods_in_window, const RegimeSettings& settings) {
  Regime regime;
  regime.impacts_per_period = std::numeric_limits<double>::quiet_NaN();
  if (impacts_in_window == 0) {
    regime.kind = RegimeKind::no_impact;
    return regime;
  }
  const std::size_t count = samples.size();
  if (count < static_cast<std::size_t>(2 * settings.max_period)) return regime;  // too few to tell: irregular
  auto coordinates = [](const PoincareSample& p) {
    return std::array<double, 4>{p.displacement_m[0], p.velocity_m_s[0], p.displacement_m[1], p.velocity_m_s[1]};
  };
  for (int n = 1; n <= settings.max_period; ++n) {
    bool repeats = true;
    for (std::size_t k = 0; k + n < count && repeats; ++k) {
      const auto a = coordinates(samples[k]), b = coordinates(samples[k + n]);
      for (int j = 0; j < 4 && repeats; ++j)
        if (std::abs(a[j] - b[j]) > settings.relative_tolerance * scale[j]) repeats = false;
    }
    if (repeats) {
      regime.kind = RegimeKind::periodic;
      regime.period = n;
      regime.impacts_per_period =
          periods_in_window > 0 ? impacts_in_window * n / periods_in_window : std::numeric_limits<double>::quiet_NaN();
      return regime;
    }
  }
  return regime;
}

}  // namespace ib
