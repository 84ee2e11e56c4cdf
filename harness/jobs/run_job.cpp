#include "harness/jobs/run_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "harness/jobs/shard_plan.h"
#include "harness/records/number_text.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "physics/modal_model.h"

namespace ib {

std::string options_text(const std::map<std::string, std::string>& options) {
  std::string text;
  for (const auto& [k, v] : options) text += (text.empty() ? "" : ";") + k + "=" + v;
  return text;
}

std::string job_id(const std::string& scenario_name, const JobSpec& job) {
  std::ostringstream id;
  id << scenario_name << "/" << job.engine << "/" << to_string(job.settings.law);
  if (job.settings.time_step_s > 0) id << "/dt=" << job.settings.time_step_s;
  const std::string options = options_text(job.settings.options);
  if (!options.empty()) id << "/" << options;
  if (job.start.index > 0) id << "/start=" << job.start.index;
  return id.str();
}

MetricSettings metric_settings(const Scenario& scenario, const Measurement& measurement) {
  MetricSettings m;
  m.window = scoring_window(scenario, measurement.window_s);
  m.excitation_frequency_hz = motor_frequency_hz(scenario);
  m.natural_frequency_hz = frame1_first_frequency_hz(scenario);
  m.sensor_rate_hz = measurement.sensor_rate_hz;
  m.merge_window_s = measurement.merge_window_s;
  return m;
}

std::string window_in_transient_warning(const Scenario& scenario, const Measurement& measurement) {
  const double window_start_s = scoring_window(scenario, measurement.window_s).start_s;
  const double transient_s = start_up_transient_s(scenario);
  if (window_start_s >= transient_s) return "";
  // the numbers as the stderr line always printed them (%g, %.3g); the name unbounded
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, "starts at %g s, before the start-up transient's end (%.3g s", window_start_s,
                transient_s);
  return scenario.name + ": the scoring window " + numbers +
         ", in which a first mode's free response decays to 5 %: ln(20) / (zeta omega_1)); impacts may settle it "
         "sooner, but the metrics may include start-up motion";
}

std::string warn_if_window_in_transient(const Scenario& scenario, const Measurement& measurement) {
  const std::string warning = window_in_transient_warning(scenario, measurement);
  if (!warning.empty()) std::fprintf(stderr, "impactbench: warning: %s\n", warning.c_str());
  return warning;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

namespace {

// The timed runs: the run again, `repeats` times, its results dropped; the record's cost becomes their
// median. The same simulator object and settings as the logged run, so the same model is built.
void time_runs(Simulator& simulator, const Scenario& scenario, const RunSettings& settings, int repeats,
               RunRecord& record) {
  if (repeats <= 0) return;
  std::vector<double> wall_s, cpu_s;
  for (int i = 0; i < repeats; ++i) {
    const RunCost cost = simulator.run(scenario, settings).cost;
    wall_s.push_back(cost.wall_time_s);
    cpu_s.push_back(cost.cpu_time_s);
  }
  record.timed_runs = repeats;
  record.cost.wall_time_s = median(wall_s);
  record.cost.cpu_time_s = median(cpu_s);
  record.wall_time_min_s = *std::min_element(wall_s.begin(), wall_s.end());
  record.wall_time_max_s = *std::max_element(wall_s.begin(), wall_s.end());
  record.cpu_time_min_s = *std::min_element(cpu_s.begin(), cpu_s.end());
  record.cpu_time_max_s = *std::max_element(cpu_s.begin(), cpu_s.end());
}

// The machine's 1-minute load average now (NaN where the system cannot tell): beside a run's time, it
// says how much the other processes of a shared machine were competing for the cores.
double load_average_now() {
  double load[1];
  return getloadavg(load, 1) == 1 ? load[0] : std::numeric_limits<double>::quiet_NaN();
}

// Accuracy is judged against the reference on the engine's own chain when there is one: that
// isolates the engine's contact handling and time stepping (its errors against the beam, the whole
// error a user sees, are in the record beside it). Only a stable run (verdict ok) is judged, and
// never a reference: a reference is what others are judged against (the chain reference's distance
// from the beam is the discretisation's, reported as data).
void judge_accuracy_of(RunRecord& record, const Measurement& measurement, const std::string& missing_reference) {
  if (record.engine == "reference" || record.verdict != Verdict::ok) return;
  if (!missing_reference.empty()) {
    record.reason = "stable; accuracy not available: " + missing_reference;
    return;
  }
  const bool on_chain = record.errors_vs_chain_reference.has_value();
  const auto& accuracy_errors = on_chain ? record.errors_vs_chain_reference : record.errors_vs_reference;
  if (!accuracy_errors) return;
  const Judgement accuracy = judge_accuracy(*accuracy_errors, measurement.verdicts, on_chain ? "own chain" : "beam");
  record.verdict = accuracy.verdict;
  record.reason = accuracy.reason;
}

// The errors of a run's metrics against the references (none where a reference is missing).
void compare_with_references(RunRecord& record, const Metrics& metrics, const Trajectory& trajectory,
                             const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                             const MetricSettings& settings) {
  record.errors_vs_reference.reset();
  record.errors_vs_chain_reference.reset();
  if (beam_reference)
    record.errors_vs_reference =
        compare_metrics(metrics, trajectory, beam_reference->metrics, beam_reference->trajectory, settings);
  if (chain_reference)
    record.errors_vs_chain_reference =
        compare_metrics(metrics, trajectory, chain_reference->metrics, chain_reference->trajectory, settings);
}

}  // namespace

// The sensor's reading over the whole written series (its first window starts at the series' first
// sample, the scoring window's start unless --series all or --series-start say otherwise).
static void write_sensor_over_series(const std::string& path, const Trajectory& trajectory, double sensor_rate_hz) {
  const double start_s = trajectory.size() > 0 ? trajectory.time_s.front() : 0.0;
  const double end_s = trajectory.size() > 0 ? trajectory.time_s.back() : 0.0;
  const SensorSeries frame1 = sensor_acceleration(trajectory, 0, start_s, end_s, sensor_rate_hz);
  const SensorSeries frame2 = sensor_acceleration(trajectory, 1, start_s, end_s, sensor_rate_hz);
  write_sensor_csv(path, frame1.time_s, {frame1.acceleration_m_s2, frame2.acceleration_m_s2});
}

void check_scoring_window(const Scenario& scenario, const Measurement& measurement) {
  const ScoringWindow window = scoring_window(scenario, measurement.window_s);
  const double length_s = window.end_s - window.start_s;
  const double sensor_period_s = 1.0 / measurement.sensor_rate_hz;
  const double motor_period_s = scenario.motor ? 1.0 / motor_frequency_hz(scenario) : 0.0;
  const double shortest_s = std::max(sensor_period_s, motor_period_s);
  if (length_s >= shortest_s) return;
  const std::string where = scenario.source_path.empty() ? scenario.name : scenario.source_path;
  const std::string given = measurement.window_s
                                ? "--window " + number_text(*measurement.window_s)
                                : where + ": [scenario] scoring_window_s = " + number_text(scenario.scoring_window_s);
  const std::string what = motor_period_s > sensor_period_s
                               ? "one motor period of " + where + " (" + number_text(motor_period_s) +
                                     " s): impacts per cycle are not measured over less"
                               : "one sensor sample (1 / " + number_text(measurement.sensor_rate_hz) + " Hz)";
  throw std::invalid_argument(given + ": scores " + number_text(length_s) + " s; allowed: at least " + what);
}

Scenario started_as(const Scenario& scenario, const EnsembleStart& start) {
  Scenario started = scenario;
  started.initial.frame1_tip_displacement_m += start.initial_displacement_offset_m;
  return started;
}

RunRecord run_job(const Scenario& scenario_as_written, const JobSpec& job, const Measurement& measurement,
                  const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                  const std::string& run_folder, ReferenceData* keep, const SimulatorFactory& factory) {
  const Scenario scenario = started_as(scenario_as_written, job.start);
  check_scoring_window(scenario, measurement);
  auto simulator = factory(job.engine);
  if (!simulator) throw std::invalid_argument("engine '" + job.engine + "' is not in this build");
  const MetricSettings metrics_settings = metric_settings(scenario, measurement);
  RunSettings settings = job.settings;
  if (settings.series_start_s < 0)
    settings.series_start_s = measurement.series == SeriesOutput::all ? 0.0 : metrics_settings.window.start_s;
  // the engines' divergence guard stops a run at the bound the verdict then judges it by: one record
  settings.stability = measurement.verdicts.stability;

  RunRecord record;
  record.job_id = job_id(scenario.name, job);
  record.scenario = scenario.name;
  record.scenario_file = scenario.source_path;
  if (!scenario.source_path.empty()) {
    record.scenario_digest = file_digest(scenario.source_path);
    std::error_code error;
    record.scenario_file_absolute = std::filesystem::absolute(scenario.source_path, error).lexically_normal();
  }
  record.engine = simulator->name();
  record.engine_version = simulator->version();
  record.law = to_string(settings.law);
  record.time_step_s = settings.time_step_s;
  record.options = options_text(settings.options);
  record.duration_s = scenario.duration_s;
  record.window = metrics_settings.window;
  record.output_rate_hz = settings.output_rate_hz;
  record.warnings = job.warnings;
  record.start = job.start;
  // A window the caller chose (--window) on a start from rest: `impactbench run`'s case. A suite's or a
  // sweep's plan has put it in job.warnings already (a suite's also for a cut --duration): not twice.
  if (measurement.window_s && !settings.initial_state)
    if (std::string w = window_in_transient_warning(scenario, measurement);
        !w.empty() && std::find(record.warnings.begin(), record.warnings.end(), w) == record.warnings.end())
      record.warnings.push_back(w);

  const double load_at_start = load_average_now();
  RunResult result = simulator->run(scenario, settings);
  record.load_average = 0.5 * (load_at_start + load_average_now());
  record.cost = result.cost;
  record.logged_wall_time_s = result.cost.wall_time_s;
  record.logged_cpu_time_s = result.cost.cpu_time_s;
  record.diagnostics = result.diagnostics;
  // The step and chain the simulator used, also when it chose them itself (its defaults): the step the
  // fixed-step loop advanced by (RunResult::time_step_s), the asked one where the run never stepped.
  if (result.time_step_s > 0) record.time_step_s = result.time_step_s;
  if (const auto links = simulator->chain_links(scenario, settings)) record.chain_links = *links;
  const Judgement stability = judge_stability(scenario, result, measurement.verdicts);
  record.verdict = stability.verdict;
  record.reason = stability.reason;
  const Metrics metrics = compute_metrics(result.trajectory, metrics_settings);
  record.metrics = metrics;
  compare_with_references(record, metrics, result.trajectory, beam_reference, chain_reference, metrics_settings);
  judge_accuracy_of(record, measurement, job.missing_reference);
  if (!run_folder.empty()) {
    std::error_code error;
    std::filesystem::create_directories(run_folder, error);
    if (error) throw OutputError(output_error_text(run_folder, "create the run folder", error.value()));
    // The series and the impact zoom (a series too), gzipped, unless --series none.
    if (measurement.series != SeriesOutput::none) {
      write_series_csv(run_folder + "/series.csv.gz", series_at_rate(result.trajectory, measurement.series_rate_hz));
      if (result.impact_zoom.size() > 0) write_series_csv(run_folder + "/impact.csv.gz", result.impact_zoom);
      write_sensor_over_series(run_folder + "/sensor.csv.gz", result.trajectory, metrics_settings.sensor_rate_hz);
    }
    write_events_csv(run_folder + "/events.csv", result.trajectory);
  }
  if (result.status != RunStatus::failed) time_runs(*simulator, scenario, settings, measurement.timed_repeats, record);
  if (!run_folder.empty()) write_summary_json(run_folder + "/summary.json", record);
  if (keep) *keep = ReferenceData{metrics, std::move(result.trajectory), std::move(result.final_state)};
  return record;
}

RunRecord score_for_law(const Scenario& scenario, const RunRecord& run, const ReferenceData& run_data,
                        const std::string& job_id, ContactLaw law, const Measurement& measurement,
                        const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                        const std::string& source_folder, const std::string& run_folder,
                        const std::string& missing_reference) {
  RunRecord record = run;
  record.job_id = job_id;
  record.law = to_string(law);
  record.same_run_as = run.job_id;
  compare_with_references(record, run_data.metrics, run_data.trajectory, beam_reference, chain_reference,
                          metric_settings(scenario, measurement));
  // Stability is the run's own; accuracy is judged again, against this law's references.
  if (record.verdict == Verdict::inaccurate || record.verdict == Verdict::ok) {
    record.verdict = Verdict::ok;
    record.reason.clear();
    judge_accuracy_of(record, measurement, missing_reference);
  }
  if (!run_folder.empty()) {
    std::error_code error;
    std::filesystem::create_directories(run_folder, error);
    if (error) throw OutputError(output_error_text(run_folder, "create the run folder", error.value()));
    // The same files, linked (no second copy on disk; copied where links are not possible).
    for (const char* name : {"series.csv.gz", "sensor.csv.gz", "events.csv", "impact.csv.gz"}) {
      const std::string from = source_folder + "/" + name, to = run_folder + "/" + name;
      if (!std::filesystem::exists(from, error)) continue;
      std::filesystem::remove(to, error);
      std::filesystem::create_hard_link(from, to, error);
      if (error) std::filesystem::copy_file(from, to, error);
      if (error) throw OutputError(output_error_text(to, "write", error.value()));
    }
    write_summary_json(run_folder + "/summary.json", record);
  }
  return record;
}

ReferenceData load_reference(const std::string& run_folder, const Scenario& scenario, const Measurement& measurement) {
  ReferenceData data;
  read_series_csv(series_file(run_folder), data.trajectory);
  read_events_csv(run_folder + "/events.csv", data.trajectory);
  // The scoring window must lie in the series (a sample of slack at each end: the series' grid need not
  // land on the run's end): metrics of a window past the data would all be NaN, and nothing would say why.
  const MetricSettings settings = metric_settings(scenario, measurement);
  const Trajectory& t = data.trajectory;
  const double slack_s = (1 + 1e-9) / t.output_rate_hz;
  const ScoringWindow& window = settings.window;
  if (window.start_s < t.time_s.front() - slack_s || window.end_s > t.time_s.back() + slack_s)
    throw std::runtime_error(series_file(run_folder) + ": holds " + exact_number_text(t.time_s.front()) + " to " +
                             exact_number_text(t.time_s.back()) + " s, but the scoring window is " +
                             exact_number_text(window.start_s) + " to " + exact_number_text(window.end_s) + " s (" +
                             scenario.source_path + " and --window); allowed: a window inside the series");
  data.metrics = compute_metrics(data.trajectory, settings);
  return data;
}

}  // namespace ib
