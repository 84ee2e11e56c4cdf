// One run as a plain record: what it was (scenario, engine, law, settings), how it ended (verdict),
// what it measured (metrics, errors against the references) and what it cost. fields() lays it out
// as named values in one fixed order, which every reporter writes (runs.csv, runs.jsonl, summary.json).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "harness/records/jsonl_table.h"
#include "harness/scoring/metrics.h"
#include "harness/scoring/verdict.h"
#include "model/scenario.h"
#include "model/trajectory.h"

namespace ib {

// Which start of an ensemble a run is (docs/results.md, "Ensembles"): runs.csv's columns ensemble_start,
// ensemble_starts and initial_displacement_offset_m.
struct EnsembleStart {
  int index = 0;                             // K, 0 .. count - 1
  int count = 1;                             // N; 1: the run is no ensemble's member
  double initial_displacement_offset_m = 0;  // added to frame 1's initial tip displacement [m]
};

struct RunRecord {
  std::string job_id;  // unique within a suite; names the run's folder
  std::string scenario, scenario_file, engine, engine_version, law;
  // In the JSON records only (summary.json, runs.jsonl): the scenario file's digest as it was run (file_digest,
  // harness/jobs/shard_plan.h) and its absolute path, so that `repro` refuses another file and works from any
  // folder. "" for a scenario made in memory.
  std::string scenario_digest, scenario_file_absolute;
  double time_step_s = 0;  // fixed-step engines [s]; 0 for the adaptive reference
  std::string options;     // simulator options as "name=value;name=value"
  // The job whose simulation this row scores against its own law's references ("" when it ran itself):
  // an engine's native contact ignores the scenario's law, so one native run answers for every law.
  std::string same_run_as;
  Verdict verdict = Verdict::ok;
  std::string reason;      // why the verdict is not ok
  bool timed_out = false;  // failed because the suite stopped it at its time limit (runs.jsonl
                           // "timed_out"): it decided nothing about the engine
  double duration_s = 0;   // simulated time [s]
  ScoringWindow window;    // the scoring window the metrics cover (columns window_start_s, window_end_s)
  double output_rate_hz = 0;
  std::optional<Metrics> metrics;                         // absent when the run produced nothing (crash, bad input)
  std::optional<MetricErrors> errors_vs_reference;        // against the continuous-beam reference
  std::optional<MetricErrors> errors_vs_chain_reference;  // against the reference on the engine's own chain
  int chain_links = 0;                                    // K of the engine's chain (0: not a chain)
  // What the run cost: the logged run's own CPU and wall time (its recording costs 1.5 to 3.9 % in
  // instructions, bench/overhead_instructions.sh, and bench/timing_check.sh shows it agrees with separate
  // timed runs within their spread), or, with timed runs (--repeat N), their median (the same run
  // repeated after the logged one, nothing recorded). Steps are the same in every run.
  RunCost cost;
  double load_average = 0;  // the machine's 1-minute load average over the logged run (mean of start and end)
  int timed_runs = 0;       // how many timed runs cost comes from (0: the logged run's)
  double wall_time_min_s = 0, wall_time_max_s = 0;          // the spread of the timed runs' wall times [s]
  double cpu_time_min_s = 0, cpu_time_max_s = 0;            // and of their CPU times [s]
  double logged_wall_time_s = 0, logged_cpu_time_s = 0;     // the logged run's own times [s]
  std::vector<std::pair<std::string, double>> diagnostics;  // simulator-specific, named with units
  // What the plan warned about this run (a scoring window inside the start-up transient): kept with its
  // results (runs.jsonl and summary.json "warnings", the report's list), not on stderr alone.
  std::vector<std::string> warnings;
  EnsembleStart start;  // which start of an ensemble the run is (the last columns)
};

// runs.csv's contact_path: an engine's option "contact" (matched when not given, simulator_options.h);
// "" for the reference, which has no contact path, and for a row without an engine (nothing ran).
std::string contact_path_of(const std::string& engine, const std::string& options_text);
// runs.csv's law_simulated: "no" on the native path (the engine used its own contact, the row's law only
// names the references it is scored against: docs/results.md), "yes" for every other run, "" without an engine.
std::string law_simulated_of(const std::string& engine, const std::string& contact_path);

// The record as a row of runs.csv / runs.jsonl (Field: jsonl_table.h). Every record yields the same names in the same
// order (missing values are NaN), so that rows of different runs line up in one table.
std::vector<Field> fields(const RunRecord& record);

// The fields that measure time rather than the physics (they differ between two runs of the same job):
// what a comparison of two suites' results leaves out.
const std::vector<std::string>& timing_field_names();

}  // namespace ib
