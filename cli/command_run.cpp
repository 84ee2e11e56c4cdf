// `run`: one scenario with one simulator and law, compared with the reference run here first.
#include "cli/commands.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <thread>

#include "harness/jobs/process_pool.h"
#include "harness/jobs/run_job.h"
#include "harness/records/number_text.h"
#include "harness/records/provenance_file.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/scoring/plausibility.h"
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
  std::printf("%s: %s%s%s\n", r.job_id.c_str(), ib::to_string(r.verdict), r.reason.empty() ? "" : ": ",
              r.reason.c_str());
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
              shown(r.time_step_s > 0 ? r.time_step_s : NAN, "%g s", "adaptive").c_str(), r.cost.steps,
              r.cost.cpu_time_s, r.cost.wall_time_s, shown(r.load_average, "%.2f", "unknown").c_str());
}

int run_and_print(const ib::Scenario& scenario, ib::JobSpec job, const ib::Measurement& measurement,
                  const std::string& engine, const std::string& out, bool window_moved) {
  if (window_moved) ib::warn_if_window_in_transient(scenario, measurement);
  // An engine is compared with the reference of the same scenario and law, run here first.
  std::optional<ib::ReferenceData> beam, chain;
  if (engine != "reference") {
    ib::JobSpec reference = job;
    reference.engine = "reference";
    reference.settings.options.clear();
    reference.settings.time_step_s = 0;
    // a reference that did not end stable is no yardstick: the run's accuracy is then "not available"
    const auto run_reference = [&](std::optional<ib::ReferenceData>& data, const char* which) {
      data.emplace();
      const ib::RunRecord r =
          ib::run_job(scenario, reference, measurement, nullptr, nullptr, "", &*data, ib::make_simulator);
      if (r.verdict == ib::Verdict::unstable || r.verdict == ib::Verdict::failed) {
        data.reset();
        job.missing_reference += std::string(job.missing_reference.empty() ? "" : "; ") + "the " + which +
                                 " reference run was " + ib::to_string(r.verdict) + " (" + r.reason + ")";
      }
    };
    run_reference(beam, "beam");
    if (const auto links = ib::make_simulator(engine)->chain_links(scenario, job.settings)) {
      reference.settings.options = ib::simulator_catalog().chain_reference_options(*links);
      // the chain's damping is the engine's choice (option chain_damping): its reference is damped alike
      if (const auto damping = job.settings.options.find("chain_damping"); damping != job.settings.options.end())
        reference.settings.options[damping->first] = damping->second;
      run_reference(chain, "chain");
    }
  }
  const ib::RunRecord record = ib::run_job(scenario, job, measurement, beam ? &*beam : nullptr,
                                           chain ? &*chain : nullptr, out, nullptr, ib::make_simulator);
  ib::write_provenance_file(out, ib::simulator_catalog());
  print_record(record);
  std::printf("  files in %s\n", out.c_str());
  return record.verdict == ib::Verdict::unstable || record.verdict == ib::Verdict::failed ? kExitRunNotOk : kExitOk;
}

// Runs `work` in a child process and waits at most time_limit_s for it: the exit code it returned, or
// nullopt when it was stopped at the limit (so that `run` ends like a suite's job, never hangs).
std::optional<int> within_time_limit(double time_limit_s, const std::function<int()>& work) {
  ib::ProcessPool pool;  // the suite's own: default signal actions in the run's process, death with the parent
  pool.start({"run", time_limit_s, /*log_path=*/"", false}, [&](int) {
    int code = kExitBadInput;
    try {
      code = work();
    } catch (const ib::OutputError& e) {
      std::fprintf(stderr, "impactbench: %s\n", e.what());
      code = kExitOutputError;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "impactbench: %s\n", e.what());
    }
    std::fflush(nullptr);
    _exit(code);
  });
  std::optional<ib::ProcessEnd> end;
  while (!(end = pool.wait_end())) {
  }
  if (end->timed_out) return std::nullopt;
  if (WIFEXITED(end->status)) return WEXITSTATUS(end->status);
  throw std::runtime_error("the run's process died of signal " + std::to_string(WTERMSIG(end->status)) + " (" +
                           strsignal(WTERMSIG(end->status)) + ")");
}

// `run`'s options, as given on the command line.
struct RunOptions {
  std::string path, engine = "reference", law = "hertz", out;
  double rate_hz = 4096;
  double series_start_s = -1;  // -1: not given, the scoring window's start
  double time_step_s = 0;      // 0: the engine's default
  std::vector<std::string> option_pairs;
  MeasurementOptions measurement;
  double time_limit_s = 600;
  double max_duration_s = 0;  // 0: the scenario's whole run
  double start_offset_m = 0;  // frame 1's initial tip displacement beyond the scenario's (an ensemble's start)
  bool force = false;         // --force: write into a folder that already holds a run
};

// --dt names a fixed step; an adaptive simulator (descriptor default_time_step_s null: its own error control
// chooses its steps) would ignore it, and its run would be labelled with a step it never took.
void refuse_step_of_adaptive(const std::string& engine, double time_step_s) {
  const ib::SimulatorDescriptor descriptor = ib::descriptor_of(ib::simulator_catalog(), engine);
  if (time_step_s == 0 || descriptor.default_time_step_s > 0) return;
  throw std::invalid_argument("--dt " + value_text(time_step_s) + ": " + engine + " takes no fixed step (" +
                              descriptor.default_time_step_note + "); allowed: no --dt with --engine " + engine +
                              ", or a fixed-step engine");
}

// A folder holding a run's files is another run's record: `run` replaces it only when asked (--force), as a
// suite refuses a folder with results unless resumed.
void refuse_existing_run_folder(const std::string& out, bool force) {
  if (force) return;
  for (const char* file : {"summary.json", "series.csv", "series.csv.gz", "events.csv"})
    if (std::filesystem::exists(std::filesystem::path(out) / file))
      throw std::invalid_argument("--out " + out + ": holds a run already (" + file +
                                  "); allowed: a new or empty folder, or --force to replace that run");
}

int command_run(const RunOptions& o) {
  ib::Scenario scenario = ib::load_scenario(o.path);
  const bool cut = ib::cut_run(scenario, o.max_duration_s);  // --duration, as a suite's
  // the run the cross checks name: the cut one's length is --duration's, not the file's
  const std::string run_length = "(" +
                                 (cut ? "--duration " + value_text(o.max_duration_s)
                                      : o.path + ": duration_s = " + value_text(scenario.duration_s)) +
                                 " s)";
  if (o.series_start_s >= scenario.duration_s)  // given (not given: -1, the scoring window's start)
    throw std::invalid_argument("--series-start " + value_text(o.series_start_s) + ": allowed: before the run's end " +
                                run_length);
  require_engine(o.engine);
  if (o.out.empty()) throw std::invalid_argument("--out '': allowed: a folder path");
  refuse_step_of_adaptive(o.engine, o.time_step_s);
  refuse_existing_run_folder(o.out, o.force);
  ib::JobSpec job;
  job.scenario_path = o.path;
  job.engine = o.engine;
  job.settings.law = parse_law(o.law);
  job.settings.output_rate_hz = o.rate_hz;
  job.settings.series_start_s = o.series_start_s;
  job.settings.time_step_s = o.time_step_s;
  job.settings.options = parse_engine_options(o.option_pairs, o.engine);
  // an ensemble's start (repro writes it): frame 1's tip displaced beyond the scenario's initial displacement
  job.start.initial_displacement_offset_m = o.start_offset_m;
  if (o.time_step_s != 0 || o.engine == "reference")
    ib::check_run_size(scenario, job.settings);  // --dt 1e300: not 0 steps, ok
  else {                                         // the engine's default step is its own: the rest of the size
    ib::RunSettings sized = job.settings;
    sized.time_step_s = 0;
    ib::check_run_size(scenario, sized);
  }
  const ib::Measurement measurement = o.measurement.build();
  require_series_resolves_sensor(o.rate_hz, measurement.sensor_rate_hz);
  if (measurement.window_s)
    require_at_most(Shared::window, *measurement.window_s, scenario.duration_s, "the run " + run_length);
  const bool window_moved = cut || measurement.window_s;
  const std::optional<int> code = within_time_limit(
      o.time_limit_s, [&]() { return run_and_print(scenario, job, measurement, o.engine, o.out, window_moved); });
  if (code) return *code;
  // recorded as a suite records a job past its limit
  ib::RunRecord record;
  record.job_id = ib::job_id(scenario.name, job);
  record.scenario = scenario.name;
  record.scenario_file = o.path;
  record.engine = o.engine;
  record.law = ib::to_string(job.settings.law);
  record.time_step_s = o.time_step_s;
  record.verdict = ib::Verdict::failed;
  record.reason = "stopped at the time limit of " + ib::number_text(o.time_limit_s) + " s (--time-limit)";
  record.timed_out = true;
  record.duration_s = scenario.duration_s;
  std::filesystem::create_directories(o.out);
  ib::write_summary_json(o.out + "/summary.json", record);
  ib::write_provenance_file(o.out, ib::simulator_catalog());
  std::printf("%s: failed: %s\n  files in %s\n", record.job_id.c_str(), record.reason.c_str(), o.out.c_str());
  return kExitRunNotOk;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* run = app.add_subcommand(
      "run", "run one scenario with one engine and law; write DIR/summary.json, series.csv, events.csv");
  run->add_option("scenario", o->path, "scenario file (.toml)")->required();
  run->add_option("--engine", o->engine, "simulator (see 'impactbench list')")->capture_default_str();
  run->add_option("--law", o->law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  run->add_option("--out", o->out, "output folder")->required();
  add_shared_option(run, Shared::rate, o->rate_hz, "output series sample rate [Hz]");
  add_shared_option(run, Shared::series_start, o->series_start_s,
                    "first output sample [s]; default: start of the scoring window", false);
  add_shared_option(run, Shared::dt, o->time_step_s, "time step of fixed-step engines [s]; default: each engine's",
                    false);
  add_shared_option(run, Shared::duration, o->max_duration_s,
                    "run a scenario longer than this for this long only, keeping its scoring window [s]", false);
  run->add_option("--option", o->option_pairs,
                  "simulator option name=value or ENGINE.name=value (ENGINE: --engine's), repeatable (see "
                  "'impactbench list')");
  run->add_flag("--force", o->force, "replace the run a folder given to --out holds already");
  run->add_option("--start-offset", o->start_offset_m,
                  "frame 1's initial tip displacement beyond the scenario's, as an ensemble's start [m]")
      ->check(CLI::Range(-0.01, 0.01));
  o->measurement.add_to(run, /*with_timing=*/true);
  add_shared_option(run, Shared::time_limit, o->time_limit_s,
                    "the run (its references included) is stopped past this and recorded as failed [s]");
  return {run, [o] { return command_run(*o); }};
}

}  // namespace cli
