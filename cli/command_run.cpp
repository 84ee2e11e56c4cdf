// `run`: one scenario with one simulator and law, compared with the reference run here first.
#include "cli/commands.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "harness/run_job.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

// A number for a person: "n/a (why)" instead of nan.
std::string shown(double value, const char* format, const char* why_not) {
  if (!std::isfinite(value)) return std::string("n/a (") + why_not + ")";
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

void print_record(const ib::RunRecord& r) {
  std::printf("%s: %s%s%s\n", r.job_id.c_str(), ib::to_string(r.verdict), r.reason.empty() ? "" : ": ", r.reason.c_str());
  if (r.metrics) {
    const ib::Metrics& m = *r.metrics;
    std::printf("  impacts %d (%d onsets), impacts per cycle %s, mean contact duration %s\n", m.impacts, m.raw_onsets,
                shown(m.impacts_per_cycle, "%.4g", "no motor").c_str(),
                shown(m.contact_duration_mean_s, "%.6g s", "no impacts").c_str());
    std::printf("  sensor peak %.4g g / %.4g g, true peak %.4g g / %.4g g (frame 1 / frame 2)\n",
                m.frames[0].sensor_peak_acceleration_g, m.frames[1].sensor_peak_acceleration_g,
                m.frames[0].true_peak_acceleration_g, m.frames[1].true_peak_acceleration_g);
  }
  if (r.errors_vs_reference) {
    const ib::MetricErrors& e = *r.errors_vs_reference;
    std::printf("  against the beam reference: sensor peak %s / %s, contact duration %s, impacts per cycle %s\n",
                shown(100 * e.sensor_peak_relative_error[0], "%+.3g %%", "no peak").c_str(),
                shown(100 * e.sensor_peak_relative_error[1], "%+.3g %%", "no peak").c_str(),
                shown(100 * e.contact_duration_relative_error, "%+.3g %%", "no impacts").c_str(),
                shown(e.impacts_per_cycle_difference, "%+.3g", "no motor").c_str());
  }
  std::printf("  time step %s, %lld steps, CPU time %.3f s, wall time %.3f s (load average %s)\n",
              shown(r.time_step_s > 0 ? r.time_step_s : NAN, "%g s", "adaptive").c_str(), r.cost.steps, r.cost.cpu_time_s, r.cost.wall_time_s,
              shown(r.load_average, "%.2f", "unknown").c_str());
}

}  // namespace

int command_run(const std::string& path, const std::string& engine, const std::string& law_name, const std::string& out,
                double rate_hz, double series_start_s, double time_step_s, const std::vector<std::string>& option_pairs,
                const MeasurementOptions& measurement_options) {
  const ib::Scenario scenario = ib::load_scenario(path);
  require_engine(engine);
  if (!(rate_hz > 0)) throw std::invalid_argument("--rate " + std::to_string(rate_hz) + ": allowed: > 0 Hz");
  ib::JobSpec job;
  job.scenario_path = path;
  job.engine = engine;
  job.settings.law = parse_law(law_name);
  job.settings.output_rate_hz = rate_hz;
  job.settings.series_start_s = series_start_s;
  job.settings.time_step_s = time_step_s;
  job.settings.options = parse_options(option_pairs);
  const ib::Measurement measurement = measurement_options.build();
  if (measurement.window_s) ib::warn_if_window_in_transient(scenario, measurement);
  // An engine is compared with the reference of the same scenario and law, run here first.
  std::optional<ib::ReferenceData> beam, chain;
  if (engine != "reference") {
    ib::JobSpec reference = job;
    reference.engine = "reference";
    reference.settings.options.clear();
    reference.settings.time_step_s = 0;
    beam.emplace();
    ib::run_job(scenario, reference, measurement, nullptr, nullptr, "", &*beam, ib::make_simulator);
    if (const auto links = ib::make_simulator(engine)->chain_links(scenario, job.settings)) {
      reference.settings.options = ib::simulator_catalog().chain_reference_options(*links);
      chain.emplace();
      ib::run_job(scenario, reference, measurement, nullptr, nullptr, "", &*chain, ib::make_simulator);
    }
  }
  const ib::RunRecord record = ib::run_job(scenario, job, measurement, beam ? &*beam : nullptr, chain ? &*chain : nullptr, out, nullptr, ib::make_simulator);
  print_record(record);
  std::printf("  files in %s\n", out.c_str());
  return record.verdict == ib::Verdict::unstable || record.verdict == ib::Verdict::failed ? kExitRunNotOk : kExitOk;
}

}  // namespace cli
