// `sweep`: the motor speed over a range of ratios to f_1, from rest or continued up and down (harness/sweep/sweep.h).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <utility>

#include "cli/commands.h"
#include "harness/records/number_text.h"
#include "harness/scoring/plausibility.h"
#include "harness/sweep/sweep.h"

namespace cli {

namespace {

// The reference's ensemble of starts from rest (SweepSettings::ensemble), each range with its why.
ib::SweepSettings::StartEnsemble ensemble_from(const SweepOptions& o, const ib::SweepSettings& s) {
  // Enough to tell a fraction of a quarter from one of a half; more is a typo (each start is a run from rest).
  constexpr int kMaxStarts = 100;
  // As a suite's ensemble: every start within 1 % of the rig's 1 mm gap, far below anything physical.
  constexpr double kMaxSpread_m = 1e-5;
  ib::SweepSettings::StartEnsemble e;
  e.reference_starts = o.reference_ensemble_starts;
  e.displacement_step_m = o.ensemble_step_m;
  ib::check_option("--reference-ensemble", e.reference_starts, 1, kMaxStarts, "", true);
  if (!(e.displacement_step_m > 0) || !(e.displacement_step_m * (e.reference_starts - 1) <= kMaxSpread_m))
    throw std::invalid_argument("--ensemble-step " + ib::exact_number_text(e.displacement_step_m) +
                                ": allowed: above 0 m, with the " + std::to_string(e.reference_starts) +
                                " starts spread over at most " + ib::exact_number_text(kMaxSpread_m) +
                                " m (1 % of the rig's 1 mm gap: far below anything physical)");
  if (!o.ensemble_ratios.empty()) {
    if (e.reference_starts == 1)
      throw std::invalid_argument("--ensemble-ratios " + o.ensemble_ratios + ": needs --reference-ensemble N > 1");
    e.ratios = ib::parse_ensemble_ratios(o.ensemble_ratios, s.ratios);
  }
  if (e.reference_starts > 1 && std::find(s.starts.begin(), s.starts.end(), ib::SweepStart::rest) == s.starts.end())
    throw std::invalid_argument("--reference-ensemble " + std::to_string(e.reference_starts) +
                                ": the ensemble's starts are from rest; needs rest among --start");
  return e;
}

}  // namespace

ib::SweepSettings sweep_settings_from(const SweepOptions& o, const MeasurementOptions& measurement_options) {
  ib::SweepSettings s;
  s.scenario_path = o.scenario;
  s.ratios = ib::parse_ratios(o.ratios);
  s.starts.clear();
  for (const auto& start : split_list(o.start, "--start", "rest, up, down or both (up and down)")) {
    const auto add = [&](ib::SweepStart value) {
      if (std::find(s.starts.begin(), s.starts.end(), value) == s.starts.end()) s.starts.push_back(value);
    };
    if (start == "up" || start == "both") add(ib::SweepStart::up);
    if (start == "down" || start == "both") add(ib::SweepStart::down);
    if (start == "rest") add(ib::SweepStart::rest);
    if (start != "up" && start != "down" && start != "both" && start != "rest")
      throw std::invalid_argument("--start " + o.start +
                                  ": allowed: rest, up, down or both (up and down), comma-separated");
  }
  if (s.starts.empty())
    throw std::invalid_argument("--start '': allowed: rest, up, down or both (up and down), comma-separated");
  matrix_settings_from(o, measurement_options, s);
  // --duration, --rest-duration, --window: checked as read (option_rules.h)
  if (o.rest_duration_s >= 0) s.rest_duration_s = o.rest_duration_s;
  require_at_most(Shared::window, o.window_s, o.duration_s, "the run (--duration " + value_text(o.duration_s) + " s)");
  s.continuation_duration_s = o.duration_s;
  s.window_s = o.window_s;
  s.ensemble = ensemble_from(o, s);
  return s;
}

namespace {

int command_sweep(const SweepOptions& o, const MeasurementOptions& measurement_options) {
  const ib::SweepSettings s = sweep_settings_from(o, measurement_options);
  return sweep_exit_code(s, ib::run_sweep(s));
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto options = std::make_shared<std::pair<SweepOptions, MeasurementOptions>>();
  SweepOptions& o = options->first;
  MeasurementOptions& measurement = options->second;
  measurement.series = "none";  // a sweep's tables and Poincare samples are its results
  CLI::App* command =
      app.add_subcommand("sweep",
                         "a frequency sweep: every ratio of the motor speed to f_1 from rest, or continued "
                         "from the previous ratio's final state up and down (sweep.csv, poincare.csv)");
  command->add_option("scenario", o.scenario, "a scenario file with a motor (.toml)")->required();
  command->add_option("--ratios", o.ratios, "FROM:TO:STEP, the motor speed over frame 1's f_1")->capture_default_str();
  command
      ->add_option("--start", o.start,
                   "rest (each ratio from rest), up, down (continued from the previous ratio) or both (up and down), "
                   "comma-separated")
      ->capture_default_str();
  command
      ->add_option("--engines", o.engines,
                   "comma-separated simulators, or all; default: the reference alone (as suite's)")
      ->capture_default_str();
  command
      ->add_option("--laws", o.laws,
                   "comma-separated laws, or all; default: hertz alone, the published model (a suite runs every "
                   "law: a sweep runs each over every ratio and start, so each law more is the sweep again)")
      ->capture_default_str();
  command->add_option("--paths", o.paths, "comma-separated contact paths of the engines; default: each engine's");
  add_shared_list_option(command, Shared::dt, o.time_steps,
                         "comma-separated time steps of fixed-step engines [s]; default: each engine's");
  command->add_option("--option", o.options,
                      "engine.name=value, repeatable (e.g. reference.n=5); name=value when --engines lists one engine");
  add_shared_option(command, Shared::duration, o.duration_s, "each continued ratio's run [s], whole motor periods");
  add_shared_option(command, Shared::rest_duration, o.rest_duration_s,
                    "a start from rest's run (also a continuation's first ratio) [s]; default: the scenario's duration",
                    false);
  add_shared_option(command, Shared::window, o.window_s, "the last S seconds of each run are scored [s]");
  add_shared_option(command, Shared::rate, o.rate_hz, "output series sample rate [Hz]");
  add_shared_option(command, Shared::jobs, o.jobs, "worker processes (one chain each)");
  add_shared_option(command, Shared::time_limit, o.time_limit_s,
                    "per ratio; a chain past it is stopped and recorded [s]");
  command
      ->add_option(
          "--reference-ensemble", o.reference_ensemble_starts,
          "N: the reference from N starts from rest at each --ensemble-ratios ratio (start K: frame 1's tip displaced "
          "K x --ensemble-step); the report gives the fraction reaching each regime and the multistable ratios")
      ->capture_default_str();
  command->add_option("--ensemble-step", o.ensemble_step_m, "frame 1's initial tip displacement between two starts [m]")
      ->capture_default_str();
  command->add_option(
      "--ensemble-ratios", o.ensemble_ratios,
      "where the reference's ensemble runs: FROM:TO:STEP or single ratios, comma-separated, each one of --ratios; "
      "default: every ratio");
  command->add_option("--shard", o.shard, "K/N: run every N-th chain only (configuration and start), for a job array");
  command->add_flag("--resume", o.resume, "continue the sweep in --out: the rows recorded are kept, the rest run");
  command->add_option("--out", o.out, "output folder")->required();
  add_shared_option(command, Shared::sensor_rate, measurement.sensor_rate_hz, "accelerometer sample rate [Hz]");
  command
      ->add_option("--series", measurement.series, "what each ratio's folder keeps of its series: none, window or all")
      ->capture_default_str();
  return {command, [options] { return command_sweep(options->first, options->second); }};
}

int sweep_exit_code(const ib::SweepSettings& s, const ib::SweepOutcome& outcome) {
  const int code = exit_code(ib::result_of(ib::end_of(outcome)));  // how any campaign ends: one rule
  if (outcome.interrupted_by != 0) {
    std::fprintf(stderr, "\nimpactbench: sweep interrupted; continue with: %s\n", s.resume_command.c_str());
    return code;
  }
  if (outcome.chains_stopped > 0) {  // a chain's process got a signal from outside before the sweep did (or alone)
    std::fprintf(
        stderr, "\nimpactbench: %d chains were stopped by signal %d from outside before their end; continue with: %s\n",
        outcome.chains_stopped, outcome.stopped_by, s.resume_command.c_str());
    return code;
  }
  std::printf("sweep: %d ratios recorded in %s/sweep.csv (%d run now, %d already recorded), %d not ok\n",
              outcome.rows_run + outcome.rows_skipped, s.out.c_str(), outcome.rows_run, outcome.rows_skipped,
              outcome.not_ok);
  if (s.shard)
    std::printf("sweep: shard %s done; join the shards with: impactbench merge OUT SHARD_FOLDER ...\n",
                ib::to_string(*s.shard).c_str());
  return code;
}

}  // namespace cli
