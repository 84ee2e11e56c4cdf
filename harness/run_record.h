// One run as a plain record: what it was (scenario, engine, law, settings), how it ended (verdict),
// what it measured (metrics, errors against the references) and what it cost. fields() lays it out
// as named values in one fixed order, which every reporter writes (runs.csv, runs.jsonl, summary.json).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "metrics.h"
#include "trajectory.h"
#include "verdict.h"

namespace ib {

struct RunRecord {
  std::string job_id;                  // unique within a suite; names the run's folder
  std::string scenario, scenario_file, engine, engine_version, law;
  double time_step_s = 0;              // fixed-step engines [s]; 0 for the adaptive reference
  std::string options;                 // simulator options as "name=value;name=value"
  Verdict verdict = Verdict::ok;
  std::string reason;                  // why the verdict is not ok
  double duration_s = 0;               // simulated time [s]
  double window_start_s = 0, window_end_s = 0;  // the scoring window the metrics cover [s]
  double output_rate_hz = 0;
  std::optional<Metrics> metrics;      // absent when the run produced nothing (crash, bad input)
  std::optional<MetricErrors> errors_vs_reference;        // against the continuous-beam reference
  std::optional<MetricErrors> errors_vs_chain_reference;  // against the reference on the engine's own chain
  int chain_links = 0;                 // K of the engine's chain (0: not a chain)
  // What the run cost: the median of the timed runs (the same run repeated after the logged one, nothing
  // recorded to disk, so that the logged run's writing and first-touch costs stay out) or, when there were
  // none, the logged run's own. Wall and CPU time are each the median; steps are the same in every run.
  RunCost cost;
  int timed_runs = 0;                  // how many timed runs cost comes from (0: the logged run's)
  double wall_time_min_s = 0, wall_time_max_s = 0;  // the spread of the timed runs' wall times [s]
  double logged_wall_time_s = 0;       // the logged run's own wall time [s]
  std::vector<std::pair<std::string, double>> diagnostics;  // simulator-specific, named with units
};

struct Field {
  std::string name;                    // with its unit, e.g. "frame1_sensor_peak_acceleration_g"
  std::variant<std::string, double> value;  // NaN: not applicable or not measured
};

// Every record yields the same names in the same order (missing values are NaN), so that rows of
// different runs line up in one table.
std::vector<Field> fields(const RunRecord& record);

// The fields that measure time rather than the physics (they differ between two runs of the same job):
// what a comparison of two suites' results leaves out.
const std::vector<std::string>& timing_field_names();

}  // namespace ib
