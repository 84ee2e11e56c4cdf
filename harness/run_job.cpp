#include "run_job.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "modal_model.h"
#include "reporters.h"
#include "run_files.h"

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
  return id.str();
}

MetricSettings metric_settings(const Scenario& scenario, const Measurement& measurement) {
  MetricSettings m;
  const double window = measurement.window_s.value_or(scenario.scoring_window_s);
  m.window_end_s = scenario.duration_s;
  m.window_start_s = std::max(0.0, scenario.duration_s - window);
  m.excitation_frequency_hz = motor_frequency_hz(scenario);
  m.natural_frequency_hz = frame1_first_frequency_hz(scenario);
  m.sensor_rate_hz = measurement.sensor_rate_hz;
  m.merge_window_s = measurement.merge_window_s;
  return m;
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
}

}  // namespace

RunRecord run_job(const Scenario& scenario, const JobSpec& job, const Measurement& measurement,
                  const ReferenceData* beam_reference, const ReferenceData* chain_reference,
                  const std::string& run_folder, ReferenceData* keep, const SimulatorFactory& factory) {
  auto simulator = factory(job.engine);
  if (!simulator) throw std::invalid_argument("engine '" + job.engine + "' is not in this build");
  const MetricSettings metrics_settings = metric_settings(scenario, measurement);
  RunSettings settings = job.settings;
  if (settings.series_start_s < 0) settings.series_start_s = metrics_settings.window_start_s;

  RunRecord record;
  record.job_id = job_id(scenario.name, job);
  record.scenario = scenario.name;
  record.scenario_file = scenario.source_path;
  record.engine = simulator->name();
  record.engine_version = simulator->version();
  record.law = to_string(settings.law);
  record.time_step_s = settings.time_step_s;
  record.options = options_text(settings.options);
  record.duration_s = scenario.duration_s;
  record.window_start_s = metrics_settings.window_start_s;
  record.window_end_s = metrics_settings.window_end_s;
  record.output_rate_hz = settings.output_rate_hz;

  RunResult result = simulator->run(scenario, settings);
  record.cost = result.cost;
  record.logged_wall_time_s = result.cost.wall_time_s;
  record.diagnostics = result.diagnostics;
  const Judgement stability = judge_stability(scenario, result, measurement.verdicts);
  record.verdict = stability.verdict;
  record.reason = stability.reason;
  const Metrics metrics = compute_metrics(result.trajectory, metrics_settings);
  record.metrics = metrics;
  if (beam_reference)
    record.errors_vs_reference = compare_metrics(metrics, result.trajectory, beam_reference->metrics,
                                                 beam_reference->trajectory, metrics_settings);
  if (chain_reference)
    record.errors_vs_chain_reference = compare_metrics(metrics, result.trajectory, chain_reference->metrics,
                                                       chain_reference->trajectory, metrics_settings);
  // Accuracy is judged against the reference on the engine's own chain when there is one: that
  // isolates the engine's contact handling and time stepping.
  const auto& accuracy_errors = record.errors_vs_chain_reference ? record.errors_vs_chain_reference : record.errors_vs_reference;
  if (record.verdict == Verdict::ok && accuracy_errors) {
    const Judgement accuracy = judge_accuracy(*accuracy_errors, measurement.verdicts);
    record.verdict = accuracy.verdict;
    record.reason = accuracy.reason;
  }
  if (!run_folder.empty()) {
    std::error_code error;
    std::filesystem::create_directories(run_folder, error);
    if (error) throw OutputError(output_error_text(run_folder, "create the run folder", error.value()));
    write_series_csv(run_folder + "/series.csv", result.trajectory);
    write_events_csv(run_folder + "/events.csv", result.trajectory);
    if (result.impact_zoom.size() > 0) write_series_csv(run_folder + "/impact.csv", result.impact_zoom);
  }
  if (result.status != RunStatus::failed) time_runs(*simulator, scenario, settings, measurement.timed_repeats, record);
  if (!run_folder.empty()) write_summary_json(run_folder + "/summary.json", record);
  if (keep) *keep = ReferenceData{metrics, std::move(result.trajectory)};
  return record;
}

ReferenceData load_reference(const std::string& run_folder, const Scenario& scenario, const Measurement& measurement) {
  ReferenceData data;
  read_series_csv(run_folder + "/series.csv", data.trajectory);
  read_events_csv(run_folder + "/events.csv", data.trajectory);
  data.metrics = compute_metrics(data.trajectory, metric_settings(scenario, measurement));
  return data;
}

}  // namespace ib
