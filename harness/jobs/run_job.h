// One run from start to record: load the scenario, run the simulator, judge it, measure it, compare
// it with the references, write its folder. The `run` command and every suite job go through here,
// so that a run is measured the same way wherever it is started.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/records/run_record.h"
#include "harness/scoring/metrics.h"
#include "harness/scoring/verdict.h"
#include "model/scenario.h"
#include "model/simulator.h"

namespace ib {

struct JobSpec {
  std::string scenario_path;
  std::string engine;
  RunSettings settings;  // law, output rate, time step, options
  // Why a reference this job is compared with is not there (it failed, or a signal stopped it); "" when
  // every one is. A stable run is then "ok" for stability with its accuracy "not available: <why>" in its
  // reason: never a silent ok.
  std::string missing_reference;
  // What the plan warns about this run (warn_if_window_in_transient): copied into its record, so that a
  // warning stays with the results it is about (docs/results.md) rather than on stderr alone.
  std::vector<std::string> warnings;
  // A member of an ensemble (docs/results.md, "Ensembles"): start K of N, run with frame 1's tip displaced by
  // initial_displacement_offset_m (K x the ensemble's step) beyond the scenario's initial displacement. Start 0
  // is the scenario as written, the run a single job is; its job id has no start.
  EnsembleStart start;
};

// Which part of a run's series its folder keeps (series.csv.gz). The metrics need only the scoring window,
// and so do the errors against a reference, whose series is always kept (SuiteSettings::series).
enum class SeriesOutput { window, all, none };

// How runs are measured and judged, the same for all of a suite's runs.
struct Measurement {
  std::optional<double>
      window_s;  // --window: the last window_s of the run is scored (scoring_window()); default: the scenario's
  double sensor_rate_hz = 2048;
  double merge_window_s = 0.002;
  VerdictSettings verdicts;
  // Timed runs: after the logged run, the same run this many times more with nothing written, whose
  // median is the run's cost (RunRecord::cost). 0 (the default): the logged run's own time, which
  // bench/timing_check.sh shows agrees with timed runs within their spread, at no extra cost.
  int timed_repeats = 0;
  SeriesOutput series = SeriesOutput::window;  // what a run's folder keeps of its series
  // The rate its series.csv.gz keeps (series_at_rate, run_files.h) [Hz]; 0: the output rate. The metrics and
  // sensor.csv.gz are computed from the full series before.
  double series_rate_hz = 0;
};

// A finished reference run that other runs are compared with.
struct ReferenceData {
  Metrics metrics;
  Trajectory trajectory;
  std::optional<SavedState> final_state;  // where the run ended, to continue from (a sweep's next ratio)
};

// The median of values (0 when there are none): what a run's timed runs give as its cost.
double median(std::vector<double> values);

// "scenario/engine/law/dt=.../options": unique within a suite, and the run's folder below runs/.
std::string job_id(const std::string& scenario_name, const JobSpec& job);
std::string options_text(const std::map<std::string, std::string>& options);

MetricSettings metric_settings(const Scenario& scenario, const Measurement& measurement);

// Says on stderr when the scoring window starts before a start from rest has settled
// (start_up_transient_s): a --duration or --window that lets start-up motion into the metrics. Returns
// the warning (without the "impactbench: warning: " prefix), "" when there is none, for the record.
std::string warn_if_window_in_transient(const Scenario& scenario, const Measurement& measurement);
// The same warning's text alone, nothing printed ("" when the window starts after the transient).
std::string window_in_transient_warning(const Scenario& scenario, const Measurement& measurement);

// A window too short to measure what a run reports is refused before anything runs (std::invalid_argument naming
// --window or the scenario file's scoring_window_s, its value and what is allowed): one that holds no sensor
// sample (shorter than 1 / sensor_rate_hz), or, with a motor, less than one motor period (impacts per cycle).
void check_scoring_window(const Scenario& scenario, const Measurement& measurement);

// The scenario as an ensemble's start runs it: frame 1's initial tip displacement offset.
Scenario started_as(const Scenario& scenario, const EnsembleStart& start);

// Runs one job and returns its record; with run_folder, writes summary.json, series.csv and events.csv
// there. Throws ScenarioError / std::invalid_argument for bad input (nothing was run).
// keep_trajectory receives the trajectory when given (a reference kept for later comparisons).
RunRecord run_job(const Scenario& scenario, const JobSpec& job, const Measurement& measurement,
                  const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                  const std::string& run_folder, ReferenceData* keep, const SimulatorFactory& factory);

// A finished run (its record and what keep received) scored as the run of another law: the same
// simulation compared with that law's references and judged again for accuracy (stability does not
// depend on the references). For the native contact path, which ignores the scenario's law. With
// run_folder, writes its summary.json there and links the run's series and events files into it from
// source_folder. missing_reference: as JobSpec's, for this law's references.
RunRecord score_for_law(const Scenario& scenario, const RunRecord& run, const ReferenceData& run_data,
                        const std::string& job_id, ContactLaw law, const Measurement& measurement,
                        const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                        const std::string& source_folder, const std::string& run_folder,
                        const std::string& missing_reference);

// A finished run read back from its folder (series.csv, events.csv) with its metrics recomputed.
ReferenceData load_reference(const std::string& run_folder, const Scenario& scenario, const Measurement& measurement);

}  // namespace ib
