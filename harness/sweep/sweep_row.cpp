// One ratio of a sweep: run, measured, its Poincare samples and regime, recorded in its folder; and the sweep's
// tables made from the row folders.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "harness/jobs/recorder.h"
#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/scoring/poincare.h"
#include "harness/sweep/sweep_internal.h"
#include "physics/modal_model.h"

namespace ib::sweep_internal {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What a row says in sweep.csv, in one fixed order (missing values NaN), from its run's record. A quantity
// runs.csv also has is named and scaled as runs.csv names it (metrics.cpp flatten(), run_record.cpp fields()),
// so that one reader serves both tables (docs/sweeps.md lists the pairs).
struct RowFigures {
  std::string engine_version, verdict = "failed", reason, regime;
  bool timed_out = false;
  double time_step_s = kNaN, impacts = kNaN, impacts_per_cycle = kNaN, period = kNaN, impacts_per_period = kNaN;
  double sensor_peak_acceleration_g[2] = {kNaN, kNaN}, peak_displacement_m[2] = {kNaN, kNaN};
  double mean_approach_velocity_m_s = kNaN, contact_duration_mean_s = kNaN, samples = kNaN;
  double steps = kNaN, cpu_time_s = kNaN, wall_time_s = kNaN, load_average = kNaN;
  std::vector<std::string> warnings;  // row.json only (sweep.csv leaves lists out, as runs.csv does)
};

std::vector<Field> row_fields(const SweepRow& row, const RowScenario& at, const RowFigures& f) {
  const JobSpec& job = row.job;
  const std::string options = options_text(job.settings.options);
  const std::string path = contact_path_of(job.engine, options);
  return {
      {"id", row.id},
      {"scenario", at.scenario.name},
      {"engine", job.engine},
      {"engine_version", f.engine_version},
      {"law", to_string(job.settings.law)},
      {"options", options},
      {"contact_path", path},
      {"law_simulated", law_simulated_of(job.engine, path)},
      {"time_step_s", std::isfinite(f.time_step_s) ? f.time_step_s : job.settings.time_step_s, true},
      {"start", to_string(row.start)},
      {"ratio", row.ratio, true},
      // which of the reference's starts from rest at this ratio (runs.csv's names; 0 of 1: no ensemble)
      {"ensemble_start", static_cast<double>(job.start.index)},
      {"ensemble_starts", static_cast<double>(job.start.count)},
      {"initial_displacement_offset_m", job.start.initial_displacement_offset_m, true},
      {"motor_frequency_hz", at.motor_frequency_hz},
      {"duration_s", at.scenario.duration_s},
      {"window_s", at.scenario.scoring_window_s},
      {"verdict", f.verdict},
      {"reason", f.reason},
      {"timed_out", f.timed_out ? 1.0 : 0.0},
      {"impacts", f.impacts},
      {"impacts_per_cycle", f.impacts_per_cycle},
      {"regime", f.regime},
      {"period_n", f.period},
      {"impacts_per_period", f.impacts_per_period},
      {"frame1_sensor_peak_acceleration_g", f.sensor_peak_acceleration_g[0]},
      {"frame2_sensor_peak_acceleration_g", f.sensor_peak_acceleration_g[1]},
      {"frame1_peak_displacement_m", f.peak_displacement_m[0]},
      {"frame2_peak_displacement_m", f.peak_displacement_m[1]},
      {"mean_approach_velocity_m_s", f.mean_approach_velocity_m_s},
      {"contact_duration_mean_s", f.contact_duration_mean_s},
      {"poincare_samples", f.samples},
      {"steps", f.steps},
      {"cpu_time_s", f.cpu_time_s},
      {"wall_time_s", f.wall_time_s},
      {"load_average", f.load_average},
  };
}

void write_row(const std::string& folder, const std::vector<Field>& fields, const RowFigures& f) {
  nlohmann::ordered_json row = json_object(fields);
  row["timed_out"] = f.timed_out;  // a boolean, as runs.jsonl's (in its place among the fields)
  row["warnings"] = f.warnings;    // a list, as runs.jsonl's
  // row.json last and by rename: its presence marks the row done, never half-written
  replace_text_file(folder + "/row.json",
                    row.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
}

std::string poincare_text(const SweepRow& row, const std::vector<PoincareSample>& samples) {
  std::ostringstream text;
  text << "id,period_index,time_s,frame1_tip_displacement_m,frame1_tip_velocity_m_s,frame2_tip_displacement_m,"
          "frame2_tip_velocity_m_s\n";
  for (const PoincareSample& p : samples)
    // the states to 9 digits (number_text: beyond any regime's tolerance and the solvers' own accuracy), the
    // time exactly: a study's sweeps write tens of thousands of samples
    text << csv_escape(row.id) << ',' << p.period_index << ',' << exact_number_text(p.time_s) << ','
         << number_text(p.displacement_m[0]) << ',' << number_text(p.velocity_m_s[0]) << ','
         << number_text(p.displacement_m[1]) << ',' << number_text(p.velocity_m_s[1]) << '\n';
  return text.str();
}

}  // namespace

RowScenario row_scenario(const Scenario& base, const SweepRow& row, const SweepSettings& settings) {
  RowScenario at;
  at.scenario = base;
  at.scenario.motor->speed_ratio_to_f1 = row.ratio;
  at.scenario.motor->frequency_hz.reset();
  at.motor_frequency_hz = motor_frequency_hz(at.scenario);
  const double run_s =
      row.first_of_chain ? settings.rest_duration_s.value_or(base.duration_s) : settings.continuation_duration_s;
  const double periods = std::max(1.0, std::round(run_s * at.motor_frequency_hz));
  at.scenario.duration_s = periods / at.motor_frequency_hz;
  const double window_periods = std::clamp(std::round(settings.window_s * at.motor_frequency_hz), 1.0, periods);
  at.scenario.scoring_window_s = window_periods / at.motor_frequency_hz;
  return at;
}

std::optional<SavedState> run_sweep_row(const Scenario& base, const SweepRow& row, const SweepSettings& settings,
                                        const std::optional<SavedState>& from, const std::string& folder) {
  const RowScenario at = row_scenario(base, row, settings);
  JobSpec job = row.job;
  if (!row.first_of_chain) job.settings.initial_state = from;
  // A row without series reads its samples and events only (sweep.csv, poincare.csv): no peaks between samples.
  job.settings.peaks_between_samples = settings.measurement.series != SeriesOutput::none;
  Measurement measurement = settings.measurement;
  measurement.window_s.reset();  // the row's window is its scenario's (whole periods), not a --window
  ReferenceData kept;
  RowFigures f;
  // Only a start from rest has a start-up transient; a continued ratio starts from a settled state.
  if (row.first_of_chain)
    if (std::string w = window_in_transient_warning(at.scenario, measurement); !w.empty()) job.warnings.push_back(w);
  f.warnings = job.warnings;
  RunRecord record;
  try {
    record = run_job(at.scenario, job, measurement, nullptr, nullptr, folder, &kept, settings.simulators.make);
  } catch (const std::invalid_argument& e) {  // a state the simulator refuses, a law it lacks: recorded
    f.reason = e.what();
    std::filesystem::create_directories(folder);
    write_row(folder, row_fields(row, at, f), f);
    return std::nullopt;
  }
  // Without series (--series none, the default) a row keeps no events.csv either: the row's metrics and
  // samples are its results, and the events of every ratio's whole run were most of a study's sweep size.
  if (settings.measurement.series == SeriesOutput::none) std::filesystem::remove(folder + "/events.csv");
  f.engine_version = record.engine_version;
  f.verdict = to_string(record.verdict);
  f.reason = record.reason;
  f.time_step_s = record.time_step_s;
  f.steps = static_cast<double>(record.cost.steps);
  f.cpu_time_s = record.cost.cpu_time_s;
  f.wall_time_s = record.cost.wall_time_s;
  f.load_average = record.load_average;
  std::vector<PoincareSample> samples;
  if (record.metrics) {
    const Metrics& m = *record.metrics;
    const ScoringWindow& window = record.window;  // the one the metrics were taken over
    samples = poincare_samples(kept.trajectory, at.motor_frequency_hz, window.start_s, window.end_s);
    const Regime regime = classify_regime(samples, orbit_scale(kept.trajectory, window.start_s, window.end_s),
                                          m.impacts, m.excitation_cycles);
    f.impacts = m.impacts;
    f.impacts_per_cycle = m.impacts_per_cycle;
    f.regime = record.verdict == Verdict::ok ? regime.label() : "";
    f.period = regime.kind == RegimeKind::periodic ? regime.period : kNaN;
    f.impacts_per_period = regime.impacts_per_period;
    for (int k = 0; k < 2; ++k) {
      f.sensor_peak_acceleration_g[k] = m.frames[k].sensor_peak_acceleration_g;
      f.peak_displacement_m[k] = m.frames[k].peak_displacement_m;
    }
    f.mean_approach_velocity_m_s = m.mean_approach_velocity_m_s;
    f.contact_duration_mean_s = m.contact_duration_mean_s;
    f.samples = static_cast<double>(samples.size());
  }
  write_text_file(folder + "/poincare.csv", poincare_text(row, samples));
  const bool continues = record.verdict == Verdict::ok && kept.final_state.has_value();
  if (continues) replace_text_file(folder + "/state.txt", saved_state_text(*kept.final_state));
  write_row(folder, row_fields(row, at, f), f);
  return continues ? kept.final_state : std::nullopt;
}

void record_row_not_run(const Scenario& base, const SweepRow& row, const SweepSettings& settings,
                        const std::string& folder, const std::string& reason, bool timed_out) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw OutputError(output_error_text(folder, "create the row's folder", error.value()));
  RowFigures f;
  f.reason = reason;
  f.timed_out = timed_out;
  write_text_file(folder + "/poincare.csv", poincare_text(row, {}));
  write_row(folder, row_fields(row, row_scenario(base, row, settings), f), f);
}

std::optional<SavedState> read_row_state(const std::string& folder) {
  std::ifstream in(folder + "/state.txt");
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  return parse_saved_state(text.str(), folder + "/state.txt");
}

bool row_done(const std::string& folder) { return std::filesystem::exists(folder + "/row.json"); }

}  // namespace ib::sweep_internal

namespace ib {

int write_sweep_tables(const std::string& folder, const std::vector<std::string>& row_ids) {
  std::vector<std::string> row_folders;
  for (const std::string& id : row_ids) row_folders.push_back(folder + "/runs/" + id);
  return write_table_in_plan_order(ResultTable{folder, "sweep"}, row_folders, "row.json", {"poincare.csv"});
}

}  // namespace ib
