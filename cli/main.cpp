// impactbench: the command line. Exit codes:
//   0    every run ok (or inaccurate)
//   1    some run unstable or failed (its files and reason are still written)
//   2    bad usage or input (the message names the file, line, key or option, the value and what is allowed)
//   3    a result could not be written (full disk, unwritable folder): the message names the file, the
//        OS's reason and what to do; everything recorded before it is kept, and `suite --resume` goes on
//   4    `merge` joined what exists, but a shard lacks results (a failed array task): the message names the
//        shard, what it lacks and the command that finishes it
//   130  `suite` stopped by SIGINT (143: SIGTERM), every finished result kept; the message says how to resume
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/merge.h"
#include "simulators/catalog.h"
#include "physics/modal_model.h"
#include "reference/reference_simulator.h"
#include "harness/run_files.h"
#include "harness/run_job.h"
#include "model/scenario_toml.h"
#include "model/simulator.h"
#include "harness/suite.h"

namespace {

constexpr int kExitOk = 0, kExitRunNotOk = 1, kExitBadInput = 2, kExitOutputError = 3, kExitIncompleteMerge = 4;
constexpr int kExitInterrupted = 128;  // + the signal's number, as a shell reports a process it stopped

// The command line as typed, with --resume added when missing: what continues an interrupted suite.
std::string resume_command(int argc, char** argv) {
  std::string command = "impactbench";
  bool resume = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    resume = resume || arg == "--resume";
    const bool plain = !arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789-_=.,/:+@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    command += " " + (plain ? arg : quoted + "'");
  }
  return command + (resume ? "" : " --resume");
}
int g_argc = 0;
char** g_argv = nullptr;

// Appends the suite's command, when it started, and the verdicts' tolerances to OUT/commands.jsonl
// before the suite runs: the report names the commands that produced its folder (a study runs several
// into one folder) and states the tolerances its verdicts used.
void record_command(const std::string& out, const ib::VerdictSettings& v) {
  std::string typed = resume_command(g_argc, g_argv);
  if (std::find(g_argv, g_argv + g_argc, std::string("--resume")) == g_argv + g_argc)
    typed.resize(typed.size() - std::string(" --resume").size());
  char started[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  const nlohmann::json line = {
      {"command", typed},
      {"started_utc", started},
      {"verdict_tolerances",
       {{"sensor_peak_relative_error", v.accuracy.sensor_peak_relative},
        {"contact_duration_relative_error", v.accuracy.contact_duration_relative},
        {"impacts_per_cycle_difference", v.accuracy.impacts_per_cycle_difference},
        {"log_decrement_relative_error", v.accuracy.log_decrement_relative}}},
      {"stability_bounds",
       {{"displacement_fraction_of_length", v.stability.displacement_bound_fraction_of_length},
        {"penetration_gaps", v.stability.penetration_bound_gaps},
        {"energy_growth_relative", v.stability.energy_growth_tolerance}}}};
  std::error_code error;
  std::filesystem::create_directories(out, error);  // when it cannot, the suite reports why (exit 3)
  if (!error) ib::append_text_file(out + "/commands.jsonl", line.dump() + "\n");
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, separator);)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

// "name=value" pairs from --option.
std::map<std::string, std::string> parse_options(const std::vector<std::string>& pairs) {
  std::map<std::string, std::string> options;
  for (const std::string& pair : pairs) {
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--option " + pair + ": expected name=value");
    options[pair.substr(0, eq)] = pair.substr(eq + 1);
  }
  return options;
}

ib::ContactLaw parse_law(const std::string& name) {
  const auto law = ib::contact_law_from_string(name);
  if (!law)
    throw std::invalid_argument("law '" + name + "': unknown; allowed: hertz, viscoelastic, newton (spring-dashpot: "
                                "another name for viscoelastic)");
  return *law;
}

void require_engine(const std::string& engine) {
  for (const auto& n : ib::simulator_names())
    if (n == engine) return;
  std::string names;
  for (const auto& n : ib::simulator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("engine '" + engine + "': not in this build; allowed: " + names);
}

// How runs are measured; shared by `run` and `suite`.
struct MeasurementOptions {
  double window_s = -1, sensor_rate_hz = 2048, merge_window_s = 0.002;
  int timed_repeats = 0;  // timed runs after the logged one (0: the logged run's own time is the cost)
  std::string series = "window";
  // with_timing: the command runs simulators (run, suite), so --repeat and --series apply; score measures files only
  void add_to(CLI::App* app, bool with_timing) {
    app->add_option("--window", window_s, "scoring window: the last S seconds of the run [s]; default: the scenario's");
    app->add_option("--sensor-rate", sensor_rate_hz, "accelerometer sample rate for the sensor peak [Hz]")->capture_default_str();
    app->add_option("--merge-window", merge_window_s, "onsets closer than this are one impact [s]")->capture_default_str();
    if (with_timing)
      app->add_option("--repeat", timed_repeats,
                      "timed runs after the logged one, nothing written; their median is the run time (0: the logged run's own)")
          ->capture_default_str();
    if (with_timing)
      app->add_option("--series", series,
                      "what a run's folder keeps of its series (series.csv.gz): window (the scoring window), all "
                      "(the whole run) or none (a suite's references keep their window)")
          ->capture_default_str();
  }
  ib::Measurement build() const {
    if (!(sensor_rate_hz > 0)) throw std::invalid_argument("--sensor-rate " + std::to_string(sensor_rate_hz) + ": allowed: > 0 Hz");
    if (!(merge_window_s >= 0)) throw std::invalid_argument("--merge-window " + std::to_string(merge_window_s) + ": allowed: >= 0 s");
    ib::Measurement m;
    if (window_s >= 0) {
      if (!(window_s > 0)) throw std::invalid_argument("--window " + std::to_string(window_s) + ": allowed: > 0 s");
      m.window_s = window_s;
    }
    m.sensor_rate_hz = sensor_rate_hz;
    m.merge_window_s = merge_window_s;
    if (timed_repeats < 0 || timed_repeats > 100)
      throw std::invalid_argument("--repeat " + std::to_string(timed_repeats) + ": allowed: 0 to 100 timed runs");
    m.timed_repeats = timed_repeats;
    if (series == "window") m.series = ib::SeriesOutput::window;
    else if (series == "all") m.series = ib::SeriesOutput::all;
    else if (series == "none") m.series = ib::SeriesOutput::none;
    else throw std::invalid_argument("--series " + series + ": allowed: window, all, none");
    return m;
  }
};

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

int command_modes(const std::string& path, bool json, const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  const ib::ReferenceSettings settings = ib::reference_settings_from_options(parse_options(option_pairs));
  nlohmann::ordered_json out;
  out["scenario"] = scenario.name;
  out["mode_set"] = ib::to_string(settings.modes.set);
  for (int f = 0; f < 2; ++f) {
    const ib::ModalBasis basis = ib::frame_modes(scenario.frames[f], settings.modes);
    nlohmann::ordered_json frame;
    frame["origin"] = basis.origin;
    frame["tip_mass_kg"] = scenario.frames[f].tip_mass_kg;
    frame["tip_effective_mass_kg"] = basis.tip_effective_mass_kg();
    std::vector<double> hz, tip, zeta;
    for (int n = 0; n < basis.size(); ++n) {
      hz.push_back(basis.omega_rad_s[n] / (2 * M_PI));
      tip.push_back(basis.tip[n]);
      zeta.push_back(basis.zeta[n]);
    }
    frame["frequency_hz"] = hz;
    frame["tip_value_per_sqrt_kg"] = tip;
    frame["damping_ratio"] = zeta;
    out["frame" + std::to_string(f + 1)] = frame;
    if (!json) {
      std::printf("frame %d (%s, tip mass %.5f kg, tip effective mass %.5f kg)\n", f + 1, basis.origin.c_str(),
                  scenario.frames[f].tip_mass_kg, basis.tip_effective_mass_kg());
      std::printf("  %4s %16s %22s %14s\n", "mode", "frequency [Hz]", "tip value [1/sqrt(kg)]", "damping [-]");
      for (int n = 0; n < basis.size(); ++n) std::printf("  %4d %16.6f %22.9f %14.6g\n", n + 1, hz[n], tip[n], zeta[n]);
    }
  }
  if (json) std::cout << out.dump(2) << '\n';
  return kExitOk;
}

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
      reference.settings.options = ib::chain_reference_options(*links);
      chain.emplace();
      ib::run_job(scenario, reference, measurement, nullptr, nullptr, "", &*chain, ib::make_simulator);
    }
  }
  const ib::RunRecord record = ib::run_job(scenario, job, measurement, beam ? &*beam : nullptr, chain ? &*chain : nullptr, out, nullptr, ib::make_simulator);
  print_record(record);
  std::printf("  files in %s\n", out.c_str());
  return record.verdict == ib::Verdict::unstable || record.verdict == ib::Verdict::failed ? kExitRunNotOk : kExitOk;
}

struct SuiteOptions {
  std::vector<std::string> inputs;
  std::string engines = "reference", laws = "hertz,viscoelastic,newton", time_steps, paths, out;
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  double time_limit_s = 600, rate_hz = 4096, max_duration_s = 0;
  bool resume = false;
  std::vector<std::string> options;
  bool find_steps = false, keep_series = false;
  int steps_per_octave = 4;
  std::string step_range = "1e-6,1e-3", tolerances;
  std::string shard;  // K/N, empty: the whole suite
};

double parse_positive(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(value > 0) || !std::isfinite(value))
    throw std::invalid_argument(option + " " + text + ": allowed: a number > 0");
  return value;
}

// --find-steps with --step-range MIN,MAX and --tolerance metric=value,... (the tolerances are the verdicts': the
// search finds the largest step the verdict calls accurate)
ib::StepSearchSettings parse_step_search(const SuiteOptions& o, ib::VerdictSettings& verdicts) {
  ib::StepSearchSettings s;
  if (o.steps_per_octave < 1 || o.steps_per_octave > 64)
    throw std::invalid_argument("--steps-per-octave " + std::to_string(o.steps_per_octave) + ": allowed: 1 to 64");
  s.points_per_octave = o.steps_per_octave;
  const auto range = split(o.step_range, ',');
  if (range.size() != 2) throw std::invalid_argument("--step-range " + o.step_range + ": expected MIN,MAX in seconds, e.g. 1e-6,1e-3");
  s.min_step_s = parse_positive(range[0], "--step-range");
  s.max_step_s = parse_positive(range[1], "--step-range");
  if (s.min_step_s > s.max_step_s) throw std::invalid_argument("--step-range " + o.step_range + ": allowed: MIN <= MAX");
  for (const auto& pair : split(o.tolerances, ',')) {
    const auto eq = pair.find('=');
    const std::string name = pair.substr(0, eq);
    bool known = false;
    for (ib::HeadlineMetric m : ib::kHeadlineMetrics) {
      if (eq == std::string::npos || name != ib::to_string(m)) continue;
      const double value = parse_positive(pair.substr(eq + 1), "--tolerance " + name + "=");
      if (m == ib::HeadlineMetric::frame1_sensor_peak) verdicts.accuracy.sensor_peak_relative = value;
      if (m == ib::HeadlineMetric::contact_duration) verdicts.accuracy.contact_duration_relative = value;
      if (m == ib::HeadlineMetric::impacts_per_cycle) verdicts.accuracy.impacts_per_cycle_difference = value;
      known = true;
    }
    if (!known)
      throw std::invalid_argument("--tolerance " + pair +
                                  ": expected metric=value with metric frame1_sensor_peak (relative), contact_duration "
                                  "(relative) or impacts_per_cycle (absolute)");
  }
  ib::step_grid(s);  // fail now on a range the grid cannot take
  return s;
}

int command_suite(const SuiteOptions& o, const MeasurementOptions& measurement_options) {
  ib::SuiteSettings s;
  s.simulators = ib::simulator_catalog();
  s.inputs = o.inputs.empty() ? std::vector<std::string>{std::string(IMPACTBENCH_SCENARIO_DIR) + "/paper"} : o.inputs;
  s.engines = split(o.engines, ',');
  for (const auto& e : s.engines) require_engine(e);
  s.laws.clear();
  for (const auto& l : split(o.laws, ',')) s.laws.push_back(parse_law(l));
  for (const auto& dt : split(o.time_steps, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(dt, &used);
    } catch (const std::exception&) {
    }
    if (used != dt.size() || !(value > 0)) throw std::invalid_argument("--dt " + dt + ": allowed: time steps > 0 s, comma-separated");
    s.time_steps_s.push_back(value);
  }
  for (const auto& path : split(o.paths, ',')) {
    if (path != "matched" && path != "injected" && path != "native")
      throw std::invalid_argument("--paths " + path + ": allowed: matched, injected, native, comma-separated");
    s.contact_paths.push_back(path);
  }
  if (o.jobs < 1) throw std::invalid_argument("--jobs " + std::to_string(o.jobs) + ": allowed: >= 1");
  if (!(o.time_limit_s > 0)) throw std::invalid_argument("--time-limit: allowed: > 0 s");
  // --option ENGINE.NAME=VALUE
  for (const auto& pair : o.options) {
    const auto dot = pair.find('.'), eq = pair.find('=');
    if (dot == std::string::npos || eq == std::string::npos || dot > eq)
      throw std::invalid_argument("--option " + pair + ": expected engine.name=value, e.g. reference.n=5");
    const std::string engine = pair.substr(0, dot);
    require_engine(engine);
    auto& target = engine == "reference" ? s.reference_options : s.engine_options[engine];
    target[pair.substr(dot + 1, eq - dot - 1)] = pair.substr(eq + 1);
  }
  for (const auto& engine : s.engines) {  // fail now, not in every job
    ib::RunSettings run;
    run.options = engine == "reference" ? s.reference_options : s.engine_options[engine];
    ib::make_simulator(engine)->check_settings(run);
  }
  s.output_rate_hz = o.rate_hz;
  if (o.max_duration_s < 0) throw std::invalid_argument("--duration: allowed: > 0 s");
  s.max_duration_s = o.max_duration_s;
  s.jobs = o.jobs;
  s.time_limit_s = o.time_limit_s;
  s.out = o.out;
  s.resume = o.resume;
  s.measurement = measurement_options.build();
  if (!o.shard.empty()) s.shard = ib::parse_shard(o.shard);
  s.resume_command = resume_command(g_argc, g_argv);
  if (o.find_steps) {
    if (!s.time_steps_s.empty()) throw std::invalid_argument("--dt cannot be combined with --find-steps (the search chooses the steps)");
    s.step_search = parse_step_search(o, s.measurement.verdicts);
    s.keep_probe_series = o.keep_series;
  } else if (o.step_range != SuiteOptions{}.step_range || !o.tolerances.empty() ||
             o.steps_per_octave != SuiteOptions{}.steps_per_octave || o.keep_series) {
    throw std::invalid_argument("--step-range, --steps-per-octave, --tolerance and --keep-series need --find-steps");
  }
  record_command(o.out, s.measurement.verdicts);
  const ib::SuiteOutcome outcome = ib::run_suite(s);
  if (outcome.interrupted_by != 0) {
    // A step search plans its probes as they end, so its total is not known in advance.
    const std::string total = s.step_search ? "" : " of " + std::to_string(outcome.jobs_total);
    std::fprintf(stderr, "\nimpactbench: interrupted after %d%s jobs; continue with: %s\n",
                 outcome.jobs_skipped + outcome.jobs_run, total.c_str(), resume_command(g_argc, g_argv).c_str());
    return kExitInterrupted + outcome.interrupted_by;
  }
  std::printf("suite: %d runs recorded in %s/runs.csv (%d skipped as already done), %d unstable or failed\n",
              outcome.jobs_run, o.out.c_str(), outcome.jobs_skipped, outcome.not_ok);
  if (o.find_steps)
    std::printf("suite: %d step searches recorded in %s/steps.csv\n", outcome.step_searches, o.out.c_str());
  if (s.shard)
    std::printf("suite: shard %s done; join the shards with: impactbench merge OUT SHARD_FOLDER ...\n", o.shard.c_str());
  return outcome.not_ok > 0 ? kExitRunNotOk : kExitOk;
}

// The model an engine builds for a run, in the engine's own format, for a person to open in the
// engine's tools (MuJoCo: MJCF for its viewer; the reference: its modal model as JSON).
int command_export(const std::string& path, const std::string& engine, const std::string& law_name, const std::string& out,
                   double time_step_s, double rate_hz, const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  ib::RunSettings settings;
  settings.law = parse_law(law_name);
  settings.time_step_s = time_step_s;
  settings.output_rate_hz = rate_hz;
  settings.options = parse_options(option_pairs);
  require_engine(engine);
  const std::string text = ib::make_simulator(engine)->export_model(scenario, settings);
  if (text.empty()) {
    std::string exportable;
    for (const auto& name : ib::simulator_names())
      if (!ib::make_simulator(name)->export_model(scenario, settings).empty()) exportable += (exportable.empty() ? "" : ", ") + name;
    throw std::invalid_argument("--engine " + engine + ": no exportable model; allowed: " + exportable);
  }
  if (out.empty() || out == "-") {
    std::cout << text;
  } else {
    std::ofstream file(out);
    if (!file) throw ib::OutputError(ib::output_error_text(out, "create", errno));
    file << text;
    file.close();
    if (!file) throw ib::OutputError(ib::output_error_text(out, "write", errno));
    std::fprintf(stderr, "model written to %s\n", out.c_str());
  }
  return kExitOk;
}

// A run made elsewhere (series.csv and events.csv in the harness's format, run_files.h), measured with the
// harness's own metric code exactly as every simulator's run is; with a reference folder, its errors
// against it too (the vs_reference_* figures of runs.csv).
int command_score(const std::string& folder, const std::string& scenario_path, const std::string& reference_folder,
                  bool json, const MeasurementOptions& measurement_options) {
  const ib::Scenario scenario = ib::load_scenario(scenario_path);
  const ib::Measurement measurement = measurement_options.build();
  const ib::MetricSettings metric_settings = ib::metric_settings(scenario, measurement);
  const ib::ReferenceData run = ib::load_reference(folder, scenario, measurement);
  std::vector<std::pair<std::string, double>> figures = ib::flatten(run.metrics);
  if (!reference_folder.empty()) {
    const ib::ReferenceData reference = ib::load_reference(reference_folder, scenario, measurement);
    const ib::MetricErrors errors =
        ib::compare_metrics(run.metrics, run.trajectory, reference.metrics, reference.trajectory, metric_settings);
    for (const auto& figure : ib::flatten(errors, "vs_reference_")) figures.push_back(figure);
  }
  if (json) {
    nlohmann::ordered_json out;
    out["run_folder"] = folder;
    out["scenario_file"] = scenario_path;
    if (!reference_folder.empty()) out["reference_folder"] = reference_folder;
    out["window_start_s"] = metric_settings.window_start_s;
    out["window_end_s"] = metric_settings.window_end_s;
    for (const auto& [name, value] : figures) out[name] = std::isfinite(value) ? nlohmann::ordered_json(value) : nullptr;
    std::cout << out.dump(2) << '\n';
  } else {
    std::printf("%s scored over [%.17g, %.17g] s\n", folder.c_str(), metric_settings.window_start_s, metric_settings.window_end_s);
    for (const auto& [name, value] : figures) std::printf("  %-45s %.17g\n", name.c_str(), value);
  }
  return kExitOk;
}

// The report is made by reports/make_report.py with Debian's matplotlib (python3-matplotlib), from
// the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out) {
  // An unwritable report folder is said here, in the words of every other write error, not as a traceback.
  // (A folder without runs.csv is left to make_report.py, which says so.)
  const std::string folder = out.empty() ? suite_folder + "/report" : out;
  if (std::filesystem::exists(suite_folder + "/runs.csv")) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) throw ib::OutputError(ib::output_error_text(folder, "create the report folder", error.value()));
    if (access(folder.c_str(), W_OK) != 0)
      throw ib::OutputError(ib::output_error_text(folder, "write into the report folder", errno));
  }
  std::string command = std::string(IMPACTBENCH_PYTHON) + " " + IMPACTBENCH_SOURCE_DIR + "/reports/make_report.py '" +
                        suite_folder + "'";
  if (!out.empty()) command += " --out '" + out + "'";
  const int status = std::system(command.c_str());
  if (status != 0) throw std::runtime_error("the report could not be made (" + command + " failed)");
  return kExitOk;
}

// The shards' folders joined into one suite folder (harness/merge.h), then its report, made as `report` makes it.
int command_merge(const std::string& out, const std::vector<std::string>& shards, bool no_report) {
  const ib::MergeOutcome outcome = ib::merge_suites(ib::MergeSettings{shards, out});
  std::printf("merge: %d runs in %s/runs.csv from %zu folders (%d recorded in several, such as the references, kept once)\n",
              outcome.runs, out.c_str(), shards.size(), outcome.runs_in_several);
  if (outcome.step_rows > 0) std::printf("merge: %d step searches in %s/steps.csv\n", outcome.step_rows, out.c_str());
  std::fflush(stdout);
  for (const std::string& line : ib::merge_messages(outcome)) std::fprintf(stderr, "impactbench: %s\n", line.c_str());
  if (!no_report) command_report(out, "");
  if (outcome.complete()) return kExitOk;
  std::fprintf(stderr, "impactbench: merged what exists, but shards are incomplete or absent (see above; exit code %d)\n",
               kExitIncompleteMerge);
  return kExitIncompleteMerge;
}

int command_list(const std::string& folder) {
  std::printf("scenarios in %s:\n", folder.c_str());
  for (const std::string& file : ib::find_scenario_files(folder)) {
    try {
      const ib::Scenario s = ib::load_scenario(file);
      std::printf("  %-24s %s\n", s.name.c_str(), file.c_str());
    } catch (const std::exception& e) {
      std::printf("  (unreadable)             %s\n", e.what());
    }
  }
  std::printf("engines:");
  for (const auto& n : ib::simulator_names()) std::printf(" %s", n.c_str());
  std::printf("\nlaws: hertz viscoelastic newton\n");
  for (const auto& n : ib::simulator_names()) {
    std::printf("options of %s:\n", n.c_str());
    for (const auto& [key, help] : ib::make_simulator(n)->option_help()) std::printf("  %-18s %s\n", key.c_str(), help.c_str());
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  g_argc = argc;
  g_argv = argv;
  CLI::App app{"impactbench: a benchmark of physics engines on a two-frame vibro-impact rig"};
  app.require_subcommand(1);

  std::string scenario_path, engine = "reference", law = "hertz", out_dir, list_folder = std::string(IMPACTBENCH_SCENARIO_DIR);
  bool json = false;
  double rate_hz = 4096, series_start_s = -1, time_step_s = 0;
  std::vector<std::string> options;
  MeasurementOptions run_measurement, suite_measurement;
  SuiteOptions suite_options;

  CLI::App* modes = app.add_subcommand("modes", "each frame's natural frequencies [Hz] and tip modal values");
  modes->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  modes->add_flag("--json", json, "print JSON");
  modes->add_option("--option", options, "reference option name=value (modes=beam|beam_paper|chain, n=N, links=K)");

  CLI::App* run = app.add_subcommand("run", "run one scenario with one engine and law; write DIR/summary.json, series.csv, events.csv");
  run->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  run->add_option("--engine", engine, "simulator (see 'impactbench list')")->capture_default_str();
  run->add_option("--law", law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  run->add_option("--out", out_dir, "output folder")->required();
  run->add_option("--rate", rate_hz, "output series sample rate [Hz]")->capture_default_str();
  run->add_option("--series-start", series_start_s, "first output sample [s]; default: start of the scoring window");
  run->add_option("--dt", time_step_s, "time step of fixed-step engines [s]");
  run->add_option("--option", options, "simulator option name=value, repeatable (see 'impactbench list')");
  run_measurement.add_to(run, /*with_timing=*/true);

  CLI::App* suite = app.add_subcommand("suite", "run scenarios x laws x engines x time steps in worker processes; "
                                                "append DIR/runs.csv, DIR/runs.jsonl and DIR/runs/<job>/");
  suite->add_option("scenarios", suite_options.inputs, "scenario files or folders; default: the published scenarios");
  suite->add_option("--engines", suite_options.engines, "comma-separated engines")->capture_default_str();
  suite->add_option("--laws", suite_options.laws, "comma-separated laws")->capture_default_str();
  suite->add_option("--dt", suite_options.time_steps, "comma-separated time steps of fixed-step engines [s]");
  suite->add_option("--paths", suite_options.paths, "comma-separated contact paths of the engines: matched, injected, native; default: each engine's");
  suite->add_option("--jobs", suite_options.jobs, "worker processes")->capture_default_str();
  suite->add_option("--out", suite_options.out, "output folder")->required();
  suite->add_flag("--resume", suite_options.resume, "skip the jobs already recorded in the output folder");
  suite->add_option("--time-limit", suite_options.time_limit_s, "per job; a job past it is stopped and recorded [s]")->capture_default_str();
  suite->add_option("--rate", suite_options.rate_hz, "output series sample rate [Hz]")->capture_default_str();
  suite->add_option("--duration", suite_options.max_duration_s,
                    "run scenarios longer than this for this long only, keeping their scoring window [s]");
  suite->add_option("--option", suite_options.options, "engine.name=value, repeatable (e.g. reference.n=5)");
  suite_measurement.add_to(suite, /*with_timing=*/true);
  suite->add_flag("--find-steps", suite_options.find_steps,
                  "per scenario, law, engine and options: search the largest stable step and the largest step at "
                  "which each headline metric is within tolerance, by bisection on a geometric grid (--steps-per-octave); "
                  "writes DIR/steps.csv and DIR/steps.jsonl");
  suite->add_option("--steps-per-octave", suite_options.steps_per_octave,
                    "with --find-steps: grid steps per halving of the step (4: a ratio of 1.19; 1: a coarse search, ratio 2)")
      ->capture_default_str();
  suite->add_flag("--keep-series", suite_options.keep_series,
                  "with --find-steps: keep every probe's series.csv.gz (default: its summary and events only)");
  suite->add_option("--step-range", suite_options.step_range, "with --find-steps: MIN,MAX step searched [s]")
      ->capture_default_str();
  suite->add_option("--tolerance", suite_options.tolerances,
                    "with --find-steps: metric=value,... for frame1_sensor_peak (relative, default 0.05), "
                    "contact_duration (relative, 0.10), impacts_per_cycle (absolute, 0.05)");
  suite->add_option("--shard", suite_options.shard,
                    "K/N: run shard K of N (1 <= K <= N): every N-th engine job (with --find-steps: step search) "
                    "in planned order, and the references they need; join the shards with 'merge'");

  std::string merge_out;
  std::vector<std::string> merge_inputs;
  bool merge_no_report = false;
  CLI::App* merge = app.add_subcommand("merge", "join the folders of a suite's shards (suite --shard K/N) into one "
                                                "suite folder, then make its report");
  merge->add_option("out", merge_out, "a new or empty folder for the joined suite")->required();
  merge->add_option("shards", merge_inputs, "the shards' folders")->required();
  merge->add_flag("--no-report", merge_no_report, "join only; make the report later with 'report OUT'");

  std::string export_engine = "mujoco", export_out;
  CLI::App* export_model = app.add_subcommand("export", "write the model an engine builds for a scenario (MuJoCo: MJCF for its viewer; reference: its modal model as JSON)");
  export_model->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  export_model->add_option("--engine", export_engine, "engine")->capture_default_str();
  export_model->add_option("--law", law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  export_model->add_option("--dt", time_step_s, "time step [s] (0: the engine's default)");
  export_model->add_option("--option", options, "engine option name=value, repeatable");
  export_model->add_option("--out", export_out, "output file; default: standard output");
  double export_rate_hz = 4096;
  export_model->add_option("--rate", export_rate_hz, "reference: output sample rate of the run the model is for [Hz]")
      ->capture_default_str();

  std::string score_folder, score_scenario, score_reference;
  MeasurementOptions score_measurement;
  CLI::App* score = app.add_subcommand("score", "measure a run folder's series.csv and events.csv (from any solver) with "
                                                "the harness's metrics; print them with the names of runs.csv");
  score->add_option("run", score_folder, "folder with series.csv and events.csv in the harness's format")->required();
  score->add_option("--scenario", score_scenario, "the scenario file (.toml) the run was made for")->required();
  score->add_option("--reference", score_reference, "a run folder to compare with (adds the vs_reference_* figures)");
  score->add_flag("--json", json, "print JSON (NaN as null)");
  score_measurement.add_to(score, /*with_timing=*/false);

  std::string report_folder, report_out;
  CLI::App* report = app.add_subcommand("report", "make the report (index.html, summary.md, figures) from a suite's saved results");
  report->add_option("suite", report_folder, "a suite's output folder")->required();
  report->add_option("--out", report_out, "report folder; default: SUITE/report");

  CLI::App* list = app.add_subcommand("list", "the scenarios, engines, laws and simulator options of this build");
  list->add_option("folder", list_folder, "scenario folder")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (modes->parsed()) return command_modes(scenario_path, json, options);
    if (run->parsed())
      return command_run(scenario_path, engine, law, out_dir, rate_hz, series_start_s, time_step_s, options, run_measurement);
    if (suite->parsed()) return command_suite(suite_options, suite_measurement);
    if (report->parsed()) return command_report(report_folder, report_out);
    if (merge->parsed()) return command_merge(merge_out, merge_inputs, merge_no_report);
    if (export_model->parsed())
      return command_export(scenario_path, export_engine, law, export_out, time_step_s, export_rate_hz, options);
    if (score->parsed()) return command_score(score_folder, score_scenario, score_reference, json, score_measurement);
    return command_list(list_folder);
  } catch (const ib::OutputError& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitOutputError;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
}
