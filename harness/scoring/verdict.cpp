#include "harness/scoring/verdict.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ib {

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::ok:
      return "ok";
    case Verdict::inaccurate:
      return "inaccurate";
    case Verdict::unstable:
      return "unstable";
    case Verdict::failed:
      return "failed";
  }
  return "unknown";
}

std::optional<Verdict> verdict_from_string(const std::string& text) {
  for (Verdict v : {Verdict::ok, Verdict::inaccurate, Verdict::unstable, Verdict::failed})
    if (text == to_string(v)) return v;
  return std::nullopt;
}

namespace {

std::string describe(const char* what, double value, const char* unit, double t) {
  std::ostringstream out;
  out.precision(6);
  out << what << " = " << value << " " << unit << " at t = " << t << " s";
  return out.str();
}

}  // namespace

double penetration_bound_m(const Scenario& scenario, const VerdictSettings& settings) {
  return std::max(settings.stability.penetration_bound_gaps * scenario.gap_m,
                  settings.stability.penetration_bound_floor_m);
}

Judgement judge_stability(const Scenario& scenario, const RunResult& result, const VerdictSettings& settings) {
  if (result.status == RunStatus::failed) return {Verdict::failed, result.reason};
  if (result.status == RunStatus::unstable) return {Verdict::unstable, result.reason};
  const Trajectory& t = result.trajectory;
  if (t.size() == 0) return {Verdict::failed, "the run wrote no samples: nothing to measure"};  // never an ok of NaN
  const double penetration_bound = penetration_bound_m(scenario, settings);
  for (std::size_t k = 0; k < t.size(); ++k) {
    for (int f = 0; f < 2; ++f) {
      const double u = t.displacement_m[f][k], v = t.velocity_m_s[f][k], a = t.acceleration_m_s2[f][k];
      if (!std::isfinite(u) || !std::isfinite(v) || !std::isfinite(a)) {
        std::ostringstream why;
        why << "non-finite state of frame " << f + 1 << " at t = " << t.time_s[k] << " s (u = " << u << " m, v = " << v
            << " m/s, a = " << a << " m/s^2)";
        return {Verdict::unstable, why.str()};
      }
      const double bound = settings.stability.displacement_bound_fraction_of_length * scenario.frames[f].length_m;
      if (std::abs(u) > bound)
        return {Verdict::unstable, describe(f == 0 ? "frame 1 tip displacement |u|" : "frame 2 tip displacement |u|",
                                            std::abs(u), "m", t.time_s[k]) +
                                       ", beyond the bound " + std::to_string(bound) + " m"};
    }
    const double penetration = t.displacement_m[0][k] - t.displacement_m[1][k] - scenario.gap_m;
    if (penetration > penetration_bound)
      return {Verdict::unstable, describe("penetration", penetration, "m", t.time_s[k]) + ", beyond the bound " +
                                     std::to_string(penetration_bound) + " m"};
  }
  for (const ContactEvent& e : t.events)
    if (e.max_indentation_m > penetration_bound)
      return {Verdict::unstable, describe("penetration", e.max_indentation_m, "m", e.onset_time_s) +
                                     ", beyond the bound " + std::to_string(penetration_bound) + " m"};
  // Without a motor nothing feeds energy in: a rise beyond the tolerance is the simulator's doing.
  // Judged while the tips are apart: inside a contact, the elastic energy a simulator stores depends
  // on how it resolves the overlap within a step (a penetration not yet pushed back counts fully).
  // Compared with the energy at t = 0 where the simulator gives it: the series may start long after the
  // run did, and a run that lost most of its energy must not be judged by its swings late in the run.
  if (!scenario.motor && t.mechanical_energy_j.size() == t.size() && t.size() > 0) {
    const double initial =
        std::isfinite(t.initial_mechanical_energy_j) ? t.initial_mechanical_energy_j : t.mechanical_energy_j.front();
    for (std::size_t k = 0; k < t.mechanical_energy_j.size(); ++k) {
      const double e = t.mechanical_energy_j[k];
      const bool apart = t.contact_force_n[k] == 0 && t.displacement_m[0][k] - t.displacement_m[1][k] < scenario.gap_m;
      if (!apart) continue;
      if (e > initial * (1 + settings.stability.energy_growth_tolerance) + 1e-12) {
        std::ostringstream why;
        why.precision(6);
        why << "energy grew without input from " << initial << " J to " << e << " J at t = " << t.time_s[k] << " s";
        return {Verdict::unstable, why.str()};
      }
    }
  }
  return {};
}

Judgement judge_accuracy(const MetricErrors& e, const VerdictSettings& s, const std::string& against) {
  std::ostringstream why;
  why.precision(3);
  why << std::showpos;
  auto beyond = [&](const char* what, double error, double tolerance, bool relative) {
    if (!(std::abs(error) > tolerance)) return;  // NaN (not defined in this case) is never beyond
    why << (why.tellp() > 0 ? "; " : "") << what << " " << (relative ? 100 * error : error) << (relative ? " %" : "")
        << std::noshowpos << " (tolerance " << (relative ? 100 * tolerance : tolerance) << (relative ? " %)" : ")")
        << std::showpos;
  };
  beyond("frame 1 sensor peak", e.sensor_peak_relative_error[0], s.accuracy.sensor_peak_relative, true);
  beyond("frame 2 sensor peak", e.sensor_peak_relative_error[1], s.accuracy.sensor_peak_relative, true);
  beyond("mean contact duration", e.contact_duration_relative_error, s.accuracy.contact_duration_relative, true);
  beyond("impacts per cycle", e.impacts_per_cycle_difference, s.accuracy.impacts_per_cycle_difference, false);
  // Frame 1's decay only: frame 1 is released and its envelope decays throughout, while frame 2 starts at
  // rest and first gains from the impacts, so a fitted decrement of its peaks is not a decay rate.
  beyond("frame 1 log decrement", e.log_decrement_relative_error[0], s.accuracy.log_decrement_relative, true);
  const std::string reason = why.str();
  if (reason.empty()) return {};
  return {Verdict::inaccurate, "vs " + against + ": " + reason};
}

}  // namespace ib
