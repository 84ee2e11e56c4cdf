// Measurements the engine tests make on a run's sampled tip motion, written once: an impact from the
// indentation's zero crossings (rig.md section 5) and a free decay's frequency and damping ratio from the
// released tip's peaks. Independent of the harness's event detection, so that a test can check it too.
// With them, the cases the engines' tests share (the free vibration's first impact, its contact-free decay,
// the settled resonance) and the reference's run on the chain the engines build, each set up once.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "adapters/common/rig.h"
#include "harness/jobs/run_job.h"
#include "harness/scoring/metrics.h"
#include "model/simulator.h"
#include "model/trajectory.h"
#include "physics/link_chain.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib::testing {

// From the indentation's upward zero crossing (touch) to its downward one (separation), with the relative
// tip velocities there, both interpolated linearly between samples.
struct CrossingImpact {
  double duration_s = 0, restitution = 0, approach_m_s = 0;
};

inline std::optional<CrossingImpact> measure_impact(const Trajectory& t, double gap_m) {
  const auto indentation = [&](std::size_t k) { return t.displacement_m[0][k] - t.displacement_m[1][k] - gap_m; };
  const auto closing = [&](std::size_t k) { return t.velocity_m_s[0][k] - t.velocity_m_s[1][k]; };
  const auto crossing = [&](std::size_t k, double& time, double& rate) {
    const double a = indentation(k - 1), b = indentation(k), w = a / (a - b);
    time = t.time_s[k - 1] + w * (t.time_s[k] - t.time_s[k - 1]);
    rate = closing(k - 1) + w * (closing(k) - closing(k - 1));
  };
  double onset = 0, approach = 0, end = 0, rebound = 0;
  std::size_t k = 1;
  while (k < t.size() && !(indentation(k - 1) <= 0 && indentation(k) > 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, onset, approach);
  while (k < t.size() && !(indentation(k - 1) > 0 && indentation(k) <= 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, end, rebound);
  return CrossingImpact{end - onset, -rebound / approach, approach};
}

// Frequency and damping ratio of frame 1's tip from its positive peaks after from_s: the peaks' spacing
// gives the damped frequency, the slope of their logarithm -zeta omega (each peak refined by a parabola).
struct Decay {
  double frequency_hz = 0;
  double damping_ratio = 0;
  int peaks = 0;
};

inline Decay measure_decay(const Trajectory& t, double from_s) {
  const std::vector<double>& u = t.displacement_m[0];
  const double dt = 1 / t.output_rate_hz;
  std::vector<double> times, logs;
  for (std::size_t k = 1; k + 1 < u.size(); ++k) {
    if (t.time_s[k] < from_s || !(u[k] > 0 && u[k] > u[k - 1] && u[k] >= u[k + 1])) continue;
    const double a = u[k - 1], b = u[k], c = u[k + 1], shift = 0.5 * (a - c) / (a - 2 * b + c);
    times.push_back(t.time_s[k] + shift * dt);
    logs.push_back(std::log(b - 0.25 * (a - c) * shift));
  }
  Decay d;
  d.peaks = static_cast<int>(times.size());
  if (d.peaks < 3) return d;
  d.frequency_hz = (d.peaks - 1) / (times.back() - times.front());
  double mean_t = 0, mean_log = 0;
  for (int i = 0; i < d.peaks; ++i) mean_t += times[i] / d.peaks, mean_log += logs[i] / d.peaks;
  double sxy = 0, sxx = 0;
  for (int i = 0; i < d.peaks; ++i)
    sxy += (times[i] - mean_t) * (logs[i] - mean_log), sxx += (times[i] - mean_t) * (times[i] - mean_t);
  const double omega_d = 2 * M_PI * d.frequency_hz;
  const double ratio = (-sxy / sxx) / omega_d;  // zeta omega / omega_d = zeta / sqrt(1 - zeta^2)
  d.damping_ratio = ratio / std::sqrt(1 + ratio * ratio);
  return d;
}

// The reference's run of s with `settings` on the chain of `links` links (an engine's chain_links, or
// default_links(s): the chain the engines build by default), so that only the engine's stepping differs.
inline RunResult reference_on_chain(const Scenario& s, RunSettings settings, int links) {
  settings.options = chain_reference_options(links);
  return make_reference_simulator()->run(s, settings);
}

// An engine's run and the reference's on the chain that engine builds for the run (its chain_links: links).
struct EngineAndReference {
  RunResult engine, reference;
  int links = 0;
};
inline EngineAndReference run_with_reference(Simulator& engine, const Scenario& s, const RunSettings& settings) {
  const int links = *engine.chain_links(s, settings);
  RunResult run = engine.run(s, settings);
  return {std::move(run), reference_on_chain(s, settings, links), links};
}

// ---- The free vibration's first impact: frame 1 released 3 mm from frame 2 touches at 48 ms and parts by 49 ms.
constexpr double kFirstImpactSeriesStart_s = 0.04;  // the first impact starts at 48 ms
constexpr double kFirstImpactEnd_s = 0.055;         // and ends by 49 ms
constexpr double kFirstImpactRate_hz = 2e6;         // dense enough to place the tip crossings to 0.5 us

// The free vibration case up to just after its first impact; clip_tension: the spring-dashpot clipped at
// zero force (the law an engine whose contact only pushes realises).
inline Scenario first_impact_scenario(bool clip_tension) {
  Scenario s = paper_scenario("free_vibration");
  s.duration_s = kFirstImpactEnd_s;
  s.scoring_window_s = kFirstImpactEnd_s;
  s.contact.viscoelastic->clip_tension = clip_tension;
  return s;
}

// A run of the first impact sampled at kFirstImpactRate_hz from series_start_s: law, step h (0: the
// engine's default), options.
inline RunSettings first_impact_settings(ContactLaw law, double h, std::map<std::string, std::string> options,
                                         double series_start_s = kFirstImpactSeriesStart_s) {
  RunSettings settings;
  settings.law = law;
  settings.output_rate_hz = kFirstImpactRate_hz;
  settings.series_start_s = series_start_s;
  settings.time_step_s = h;
  settings.options = std::move(options);
  return settings;
}

// The reference's first impact on the engines' default chain.
inline CrossingImpact reference_impact(const Scenario& s, ContactLaw law,
                                       double series_start_s = kFirstImpactSeriesStart_s) {
  const RunResult r = reference_on_chain(s, first_impact_settings(law, 0, {}, series_start_s), default_links(s));
  const auto impact = measure_impact(r.trajectory, s.gap_m);
  if (!impact) throw std::runtime_error("the reference has no impact");
  return *impact;
}

// An engine's first impact with its run; throws, naming the engine, for a run that is not ok or has no impact.
struct EngineImpact {
  CrossingImpact impact;
  RunResult run;
};
inline EngineImpact engine_impact(Simulator& engine, const Scenario& s, const RunSettings& settings) {
  RunResult r = engine.run(s, settings);
  if (r.status != RunStatus::ok) throw std::runtime_error(engine.name() + " run not ok: " + r.reason);
  const auto impact = measure_impact(r.trajectory, s.gap_m);
  if (!impact) throw std::runtime_error("the " + engine.name() + " run has no impact");
  return {*impact, std::move(r)};
}

// The first impact under Newton's law at step h (sampled at 1e5 Hz from 40 ms), as the harness scores it: its
// metrics, the run, and the realised restitution's relative distance to the scenario's e. Throws, naming the
// engine, for a run that is not ok.
struct NewtonFirstImpact {
  Metrics metrics;
  RunResult run;
  double restitution_error = 0;
};
inline NewtonFirstImpact newton_first_impact(Simulator& engine, double h) {
  Scenario s = paper_scenario("free_vibration");
  s.duration_s = s.scoring_window_s = kFirstImpactEnd_s;
  RunSettings settings;
  settings.law = ContactLaw::newton;
  settings.series_start_s = kFirstImpactSeriesStart_s;
  settings.output_rate_hz = 1e5;
  settings.time_step_s = h;
  RunResult r = engine.run(s, settings);
  if (r.status != RunStatus::ok) throw std::runtime_error(engine.name() + " run not ok: " + r.reason);
  const Metrics m = compute_metrics(r.trajectory, MetricSettings{0, s.duration_s});
  const double target = s.contact.newton->restitution;
  return {m, std::move(r), std::abs(m.mean_restitution / target - 1)};
}

// ---- The free vibration without contact: the chains' first mode.

// The published free vibration without contact (gap 1 m), for 1 s. swap: the frames trade places, so that the
// released frame is the lighter one (frame 2's specification) and both chains are measured.
inline Scenario contact_free_decay(bool swap) {
  Scenario s = paper_scenario("free_vibration");
  s.gap_m = 1.0;
  s.duration_s = 1.0;
  s.scoring_window_s = 1.0;
  if (swap) std::swap(s.frames[0], s.frames[1]);
  return s;
}

// Where measure_decay starts: by then the second mode, damped at zeta omega_2 / omega_1 = 0.03, has
// decayed below 1e-3 of its start.
constexpr double kDecayMeasuredFrom_s = 0.2;

// A run of the free decay from t = 0 (spring-dashpot: no contact happens): step h (0: the engine's default), options.
inline RunSettings free_decay_settings(double h, std::map<std::string, std::string> options) {
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = 0;
  settings.time_step_s = h;
  settings.options = std::move(options);
  return settings;
}

// The released frame's chain (K = default_links) in closed form (chain_modes): its first mode.
struct ChainMode {
  double damped_frequency_hz, zeta, omega_rad_s;
};
inline ChainMode chain_mode(const Scenario& s) {
  const ModalBasis modes = chain_modes(build_link_chain(s.frames[0], default_links(s)));
  const double omega = modes.omega_rad_s[0], zeta = modes.zeta[0];
  return {omega * std::sqrt(1 - zeta * zeta) / (2 * M_PI), zeta, omega};
}

// The released frame's first mode measured on r (from kDecayMeasuredFrom_s) against the chain's: r ok, at
// least 5 peaks, the damped frequency and zeta each within its relative tolerance; `what` names the case.
inline void expect_chain_mode(const std::string& what, const Scenario& s, const RunResult& r,
                              double frequency_tolerance, double zeta_tolerance) {
  ASSERT_EQ(r.status, RunStatus::ok) << what << ": " << r.reason;
  const Decay d = measure_decay(r.trajectory, kDecayMeasuredFrom_s);
  const ChainMode mode = chain_mode(s);
  std::printf("%s: f = %.5f Hz (chain %.5f Hz, %+.4f %%), zeta = %.6f (chain %.4f, %+.2f %%), %d peaks, %.2f us/step\n",
              what.c_str(), d.frequency_hz, mode.damped_frequency_hz,
              100 * (d.frequency_hz / mode.damped_frequency_hz - 1), d.damping_ratio, mode.zeta,
              100 * (d.damping_ratio / mode.zeta - 1), d.peaks, 1e6 * r.cost.cpu_time_s / r.cost.steps);
  ASSERT_GE(d.peaks, 5) << what;
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, frequency_tolerance) << what;
  EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, zeta_tolerance) << what;
}

// Implicit (backward-Euler) hinge springs at step h add omega h / 2 to the damping ratio: measured on r, the
// added damping within added_tolerance of that (relative), the frequency within 0.5 % of the chain's.
inline void expect_backward_euler_damping(const Scenario& s, const RunResult& r, double h, double added_tolerance) {
  const Decay d = measure_decay(r.trajectory, kDecayMeasuredFrom_s);
  const ChainMode mode = chain_mode(s);
  const double added = d.damping_ratio - mode.zeta, predicted = mode.omega_rad_s * h / 2;
  std::printf("h = %g s: zeta = %.6f, added %.6f, omega h / 2 = %.6f; f = %.5f Hz (chain %.5f Hz)\n", h,
              d.damping_ratio, added, predicted, d.frequency_hz, mode.damped_frequency_hz);
  EXPECT_NEAR(added / predicted, 1, added_tolerance);
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.005);
}

// ---- The published resonance case, settled: the reference on the K = 8 chain settles by about 6 s into one
// impact every two motor cycles (0.50 per cycle) with frame 1's sensor peak near 7.9 g (7.5 g with hinge
// chain damping), and stays there through 30 s; so the run is cut to 12 s and scored over its last 6 s (42 cycles).
inline Scenario settled_resonance() {
  Scenario s = paper_scenario("resonance");
  s.duration_s = 12;
  s.scoring_window_s = 6;
  return s;
}

// An engine's run of a resonance case with the spring-dashpot law (step h, options) and the reference's on
// the engines' default chain, each measured over the scenario's scoring window (the engine's when its run is ok).
struct ResonanceComparison {
  Metrics reference, engine;
  RunResult run;
};
inline ResonanceComparison compare_resonance(Simulator& engine, const Scenario& s, double h,
                                             std::map<std::string, std::string> options) {
  const MetricSettings window = metric_settings(s, Measurement{});
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = window.window.start_s;
  ResonanceComparison c;
  c.reference = compute_metrics(reference_on_chain(s, settings, default_links(s)).trajectory, window);
  settings.time_step_s = h;
  settings.options = std::move(options);
  c.run = engine.run(s, settings);
  if (c.run.status == RunStatus::ok) c.engine = compute_metrics(c.run.trajectory, window);
  return c;
}

}  // namespace ib::testing
