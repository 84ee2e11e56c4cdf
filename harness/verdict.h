// Every run ends with a verdict a person can check: ok, inaccurate (stable, but a headline metric is
// beyond its tolerance against the reference), unstable (the trajectory itself shows it: non-finite
// state, displacement or penetration beyond a bound, energy growing without input while the tips are
// apart), or failed (the
// simulator's own error, a crash, an abort or a time-out). Instability is a finding, never hidden.
#pragma once

#include <optional>
#include <string>

#include "harness/metrics.h"
#include "model/scenario.h"
#include "model/simulator.h"

namespace ib {

enum class Verdict { ok, inaccurate, unstable, failed };
const char* to_string(Verdict verdict);
std::optional<Verdict> verdict_from_string(const std::string& text);

struct Judgement {
  Verdict verdict = Verdict::ok;
  std::string reason;  // empty when ok
};

struct VerdictSettings {
  double displacement_bound_fraction_of_length = 0.1;  // |u| beyond this x frame length: unstable [-]
  double penetration_bound_gaps = 10;                  // delta beyond this x gap (1 mm when the gap is 0) [-]
  double energy_growth_tolerance = 1e-3;               // relative rise of energy allowed without a motor [-]
  // inaccurate when any is exceeded against the reference of the same scenario and law
  double sensor_peak_tolerance = 0.10;                 // |relative error| of either frame's sensor peak [-]
  double contact_duration_tolerance = 0.10;            // |relative error| of the mean contact duration [-]
  double impacts_per_cycle_tolerance = 0.10;           // |difference| of impacts per cycle [-]
  double log_decrement_tolerance = 0.10;               // |relative error| of frame 1's free decay [-]
};

// From the simulator's own status and the trajectory alone.
Judgement judge_stability(const Scenario& scenario, const RunResult& result, const VerdictSettings& settings);

// A stable run against a reference: inaccurate when a headline metric is beyond its tolerance. The
// reason names that reference (`against`, e.g. "own chain" or "beam"), each error signed and each
// tolerance, so that a reader can check it against the table beside it: "vs own chain: frame 1 sensor
// peak +28.8 % (tolerance 10 %); ...".
Judgement judge_accuracy(const MetricErrors& errors, const VerdictSettings& settings, const std::string& against);

}  // namespace ib
