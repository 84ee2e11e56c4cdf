// Every run ends with a verdict a person can check: ok, inaccurate (stable, but a headline metric is
// beyond its tolerance against the reference), unstable (the trajectory itself shows it: non-finite
// state, displacement or penetration beyond a bound, energy growing without input while the tips are
// apart), or failed (the
// simulator's own error, a crash, an abort or a time-out). Instability is a finding, never hidden.
#pragma once

#include <optional>
#include <string>

#include "harness/scoring/metrics.h"
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

// A stable run is inaccurate when any of these is exceeded against the reference of the same scenario
// and law. The one record of accuracy: the verdict judges with it, and so does the step search
// (step_search.h: "within tolerance" is what the verdict calls accurate). Each member's key in
// commands.jsonl and metrics.json and the metrics it judges: metric_catalog.h.
struct AccuracyTolerances {
  double sensor_peak_relative = 0.10;          // |relative error| of either frame's sensor peak [-]
  double contact_duration_relative = 0.10;     // |relative error| of the mean contact duration [-]
  double impacts_per_cycle_difference = 0.10;  // |difference| of impacts per cycle [-]
  double log_decrement_relative = 0.10;        // |relative error| of frame 1's free decay [-]
};

struct VerdictSettings {
  StabilityBounds stability;  // model/simulator.h: the engines' divergence guard reads the same record
  AccuracyTolerances accuracy;
};

// The overlap of the tips beyond which a run is unstable [m]: penetration_bound_gaps gaps, at least the floor.
double penetration_bound_m(const Scenario& scenario, const VerdictSettings& settings);

// From the simulator's own status and the trajectory alone.
Judgement judge_stability(const Scenario& scenario, const RunResult& result, const VerdictSettings& settings);

// A stable run against a reference: inaccurate when a headline metric is beyond its tolerance. The
// reason names that reference (`against`, e.g. "own chain" or "beam"), each error signed and each
// tolerance, so that a reader can check it against the table beside it: "vs own chain: frame 1 sensor
// peak +28.8 % (tolerance 10 %); ...".
Judgement judge_accuracy(const MetricErrors& errors, const VerdictSettings& settings, const std::string& against);

}  // namespace ib
