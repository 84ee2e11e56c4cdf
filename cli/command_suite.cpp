// `suite`: the matrix of scenarios, laws, engines and steps (harness/suite/suite.h), or its step search.
#include "cli/commands.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/scoring/metric_catalog.h"
#include "harness/scoring/plausibility.h"
#include "harness/suite/suite.h"

namespace cli {

// Appends the suite's command, when it started, and the verdicts' tolerances to OUT/commands.jsonl
// before the suite runs: the report names the commands that produced its folder (a study runs several
// into one folder) and states the tolerances its verdicts used.
void record_command(const std::string& out, const ib::VerdictSettings& v, const std::string& note) {
  std::string typed = resume_command(g_argc, g_argv);
  if (std::find(g_argv, g_argv + g_argc, std::string("--resume")) == g_argv + g_argc)
    typed.resize(typed.size() - std::string(" --resume").size());
  if (!note.empty()) typed += " (" + note + ")";
  char started[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  // each tolerance under its key in the metric catalog (two metrics may share one: both frames' sensor peaks)
  nlohmann::json tolerances = nlohmann::json::object();
  for (const ib::ScoredMetric& m : ib::scored_metrics()) tolerances[m.tolerance_key] = ib::tolerance_of(m, v.accuracy);
  const nlohmann::json line = {{"command", typed},
                               {"started_utc", started},
                               {"verdict_tolerances", tolerances},
                               {"stability_bounds",
                                {{"displacement_fraction_of_length", v.stability.displacement_bound_fraction_of_length},
                                 {"penetration_gaps", v.stability.penetration_bound_gaps},
                                 {"penetration_floor_m", v.stability.penetration_bound_floor_m},
                                 {"energy_growth_relative", v.stability.energy_growth_tolerance}}}};
  std::error_code error;
  std::filesystem::create_directories(out, error);  // when it cannot, the suite reports why (exit 3)
  if (!error) ib::append_text_file(out + "/commands.jsonl", line.dump() + "\n");
}

namespace {

// --find-steps with --step-range MIN,MAX and --tolerance metric=value,... (the tolerances are the verdicts': the
// search finds the largest step the verdict calls accurate)
ib::StepSearchSettings parse_step_search(const SuiteOptions& o, ib::VerdictSettings& verdicts) {
  ib::StepSearchSettings s;
  if (o.steps_per_octave < 1 || o.steps_per_octave > 64)
    throw std::invalid_argument("--steps-per-octave " + std::to_string(o.steps_per_octave) + ": allowed: 1 to 64");
  s.points_per_octave = o.steps_per_octave;
  s.walk = o.step_walk;
  const auto range = split(o.step_range, ',');
  if (range.size() != 2)
    throw std::invalid_argument("--step-range " + o.step_range + ": expected MIN,MAX in seconds, e.g. 1e-6,1e-3");
  s.min_step_s = parse_positive(range[0], "--step-range");
  s.max_step_s = parse_positive(range[1], "--step-range");
  if (s.min_step_s > s.max_step_s)
    throw std::invalid_argument("--step-range " + o.step_range + ": allowed: MIN <= MAX");
  ib::check_option("--step-range MIN", s.min_step_s, ib::Plausible::kMinTimeStep_s, ib::Plausible::kMaxTimeStep_s, "s",
                   true);
  ib::check_option("--step-range MAX", s.max_step_s, ib::Plausible::kMinTimeStep_s, ib::Plausible::kMaxTimeStep_s, "s",
                   true);
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

// The ensemble's options (suite.h, SuiteSettings::ensemble), each range with its why.
ib::SuiteSettings::Ensemble ensemble_from(const SuiteOptions& o) {
  // A thousand starts of one configuration is past any confidence interval's need; more is a typo.
  constexpr int kMaxStarts = 1000;
  // The starts must differ by far less than anything physical: all of them within 1 % of the rig's 1 mm gap.
  constexpr double kMaxSpread_m = 1e-5;
  ib::SuiteSettings::Ensemble e;
  e.engine_starts = o.ensemble_starts;
  e.reference_starts = o.reference_ensemble_starts == 0 ? o.ensemble_starts : o.reference_ensemble_starts;
  e.displacement_step_m = o.ensemble_step_m;
  ib::check_option("--ensemble", e.engine_starts, 1, kMaxStarts, "", true);
  if (o.reference_ensemble_starts != 0 && (e.reference_starts < e.engine_starts || e.reference_starts > kMaxStarts))
    throw std::invalid_argument("--reference-ensemble " + std::to_string(e.reference_starts) +
                                ": allowed: 0 (--ensemble's), or " + std::to_string(e.engine_starts) +
                                " (--ensemble) to " + std::to_string(kMaxStarts) +
                                ": every engine start is compared with the reference's of the same start");
  if (!(e.displacement_step_m > 0) || !(e.displacement_step_m * (e.reference_starts - 1) <= kMaxSpread_m))
    throw std::invalid_argument("--ensemble-step " + ib::exact_number_text(e.displacement_step_m) +
                                ": allowed: above 0 m, with the " + std::to_string(e.reference_starts) +
                                " starts spread over at most " + ib::exact_number_text(kMaxSpread_m) +
                                " m (1 % of the rig's 1 mm gap: far below anything physical)");
  if (o.find_steps && e.reference_starts > 1)
    throw std::invalid_argument(
        "--ensemble and --reference-ensemble cannot be combined with --find-steps (a search's probes are single runs)");
  return e;
}

// --reference-chains K,K,...: each K as the engines' option links takes it (1..64), in increasing order, once.
std::vector<int> reference_chains_from(const std::string& text) {
  std::vector<int> links;
  if (text.empty()) return links;
  const char* allowed =
      "integers 1 <= K <= 64 (links per frame, as the engines' option links), increasing, comma-separated";
  for (const std::string& item : split_list(text, "--reference-chains", allowed)) {
    std::size_t used = 0;
    int k = 0;
    try {
      k = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || k < 1 || k > 64 || (!links.empty() && k <= links.back()))
      throw std::invalid_argument("--reference-chains '" + text + "': " + item +
                                  " is not allowed; allowed: " + allowed);
    links.push_back(k);
  }
  return links;
}

}  // namespace

ib::SuiteSettings suite_settings_from(const SuiteOptions& o, const MeasurementOptions& measurement_options) {
  ib::SuiteSettings s;
  s.inputs = o.inputs.empty() ? std::vector<std::string>{std::string(IMPACTBENCH_SCENARIO_DIR) + "/paper"} : o.inputs;
  matrix_settings_from(o, measurement_options, s);
  s.max_duration_s = o.max_duration_s;  // --duration: checked as read (option_rules.h)
  s.extend = o.extend;
  s.reference_cache = o.reference_cache;
  s.ensemble = ensemble_from(o);
  s.reference_chain_links = reference_chains_from(o.reference_chains);
  if (!s.reference_chain_links.empty() && o.find_steps)
    throw std::invalid_argument(
        "--reference-chains cannot be combined with --find-steps (a search plans its engines' probes only)");
  if (o.recommended) {
    // the configuration sets the contact path and the step of every law: a path or step beside it is a mistake
    if (!o.paths.empty() || !s.time_steps_s.empty() || o.find_steps)
      throw std::invalid_argument(
          "--recommended cannot be combined with --paths, --dt or --find-steps (each engine's "
          "recommended configuration sets its contact path and time step per law)");
    s.recommended = true;
  }
  if (o.find_steps) {
    if (!s.time_steps_s.empty())
      throw std::invalid_argument("--dt cannot be combined with --find-steps (the search chooses the steps)");
    s.step_search = parse_step_search(o, s.measurement.verdicts);
    s.keep_probe_series = o.keep_series;
  } else if (o.step_range != SuiteOptions{}.step_range || !o.tolerances.empty() ||
             o.steps_per_octave != SuiteOptions{}.steps_per_octave || o.keep_series || o.step_walk) {
    throw std::invalid_argument(
        "--step-range, --steps-per-octave, --step-walk, --tolerance and --keep-series need --find-steps");
  }
  return s;
}

int suite_exit_code(const ib::SuiteSettings& s, const ib::SuiteOutcome& outcome) {
  const int code = exit_code(ib::result_of(ib::end_of(outcome)));  // how any campaign ends: one rule
  if (outcome.interrupted_by != 0) {
    // A step search plans its probes as they end, so its total is not known in advance.
    const std::string total = s.step_search ? "" : " of " + std::to_string(outcome.jobs_total);
    std::fprintf(stderr, "\nimpactbench: interrupted after %d%s jobs; continue with: %s\n",
                 outcome.jobs_skipped + outcome.jobs_run, total.c_str(), s.resume_command.c_str());
    return code;
  }
  if (outcome.jobs_stopped > 0) {  // a worker got a signal from outside before the suite did (or alone)
    std::fprintf(stderr,
                 "\nimpactbench: %d jobs are not recorded: stopped by signal %d from outside, or compared with a "
                 "reference that was; run them with: %s\n",
                 outcome.jobs_stopped, outcome.stopped_by, s.resume_command.c_str());
    return code;
  }
  std::printf(
      "suite: %d runs recorded in %s/runs.csv (%d skipped as already done), %d unstable or failed; "
      "of all %d results there, %d unstable or failed\n",
      outcome.jobs_run, s.out.c_str(), outcome.jobs_skipped, outcome.not_ok, outcome.recorded, outcome.not_ok_recorded);
  if (!s.reference_cache.empty())
    std::printf("suite: %d reference runs copied from %s, not solved\n", outcome.references_from_cache,
                s.reference_cache.c_str());
  if (s.step_search)
    std::printf("suite: %d step searches recorded in %s/steps.csv\n", outcome.step_searches, s.out.c_str());
  if (s.shard)
    std::printf("suite: shard %s done; join the shards with: impactbench merge OUT SHARD_FOLDER ...\n",
                ib::to_string(*s.shard).c_str());
  return code;  // every result, also those of an earlier invocation
}

namespace {

int command_suite(const SuiteOptions& o, const MeasurementOptions& measurement_options) {
  const ib::SuiteSettings s = suite_settings_from(o, measurement_options);
  record_command(o.out, s.measurement.verdicts, "");
  return suite_exit_code(s, ib::run_suite(s));
}

}  // namespace

Command add_suite_command(CLI::App& app) {
  auto options = std::make_shared<std::pair<SuiteOptions, MeasurementOptions>>();
  SuiteOptions& o = options->first;
  CLI::App* suite = app.add_subcommand("suite",
                                       "run scenarios x laws x engines x time steps in worker processes; "
                                       "append DIR/runs.csv, DIR/runs.jsonl and DIR/runs/<job>/");
  suite->add_option("scenarios", o.inputs, "scenario files or folders; default: the published scenarios");
  suite
      ->add_option("--engines", o.engines,
                   "comma-separated engines, or all; default: the reference alone, the yardstick every run is scored "
                   "against (as sweep and a study part's default)")
      ->capture_default_str();
  suite->add_option("--laws", o.laws, "comma-separated laws, or all")->capture_default_str();
  add_shared_list_option(suite, Shared::dt, o.time_steps, "comma-separated time steps of fixed-step engines [s]");
  suite->add_option("--paths", o.paths,
                    "comma-separated contact paths of the engines: matched, injected, native; default: each engine's");
  add_shared_option(suite, Shared::jobs, o.jobs, "worker processes");
  suite->add_option("--out", o.out, "output folder")->required();
  suite->add_flag("--resume", o.resume,
                  "continue the suite recorded in the output folder (same settings): skip the jobs already recorded");
  suite->add_flag("--extend", o.extend,
                  "add this suite to a folder that holds suites with other settings (a study's parts); a job it shares "
                  "with the folder must have been recorded with the same settings");
  add_shared_option(suite, Shared::time_limit, o.time_limit_s, "per job; a job past it is stopped and recorded [s]");
  add_shared_option(suite, Shared::rate, o.rate_hz, "output series sample rate [Hz]");
  add_shared_option(suite, Shared::duration, o.max_duration_s,
                    "run scenarios longer than this for this long only, keeping their scoring window [s]", false);
  suite->add_option("--option", o.options,
                    "engine.name=value, repeatable (e.g. reference.n=5); name=value when --engines lists one engine");
  suite->add_option("--reference-cache", o.reference_cache,
                    "a folder that shares reference runs between output folders: a reference it holds (same scenario "
                    "content, settings and executable) is copied, not solved; one solved is stored there");
  suite
      ->add_option("--ensemble", o.ensemble_starts,
                   "N: run every configuration from N starts, start K with frame 1's tip displaced by K x "
                   "--ensemble-step; the report gives each metric and error with its confidence interval")
      ->capture_default_str();
  suite
      ->add_option("--reference-ensemble", o.reference_ensemble_starts,
                   "N: the references' starts (at least --ensemble; 0: --ensemble's): their spread says whether a "
                   "case needs an ensemble")
      ->capture_default_str();
  suite->add_option("--reference-chains", o.reference_chains,
                    "K,K,...: the reference alone on the K-link chain of every scenario, law and reference start, "
                    "scored against the beam: how the chain's resolution alone moves each metric (1 <= K <= 64)");
  suite
      ->add_option("--ensemble-step", o.ensemble_step_m,
                   "frame 1's initial tip displacement between two starts of an ensemble [m]")
      ->capture_default_str();
  options->second.add_to(suite, /*with_timing=*/true);
  suite->add_flag("--recommended", o.recommended,
                  "each engine in its authors' recommended configuration for each law: the options and time step of "
                  "its adapters/<engine>/descriptor.json, every setting with its source (docs/engines.md); not with "
                  "--paths, --dt or --find-steps");
  suite->add_flag(
      "--find-steps", o.find_steps,
      "per scenario, law, engine and options: search the largest stable step and the largest step at "
      "which each headline metric is within tolerance, by bisection on a geometric grid (--steps-per-octave); "
      "writes DIR/steps.csv and DIR/steps.jsonl");
  suite
      ->add_option(
          "--steps-per-octave", o.steps_per_octave,
          "with --find-steps: grid steps per halving of the step (4: a ratio of 1.19; 1: a coarse search, ratio 2)")
      ->capture_default_str();
  suite->add_flag("--step-walk", o.step_walk,
                  "with --find-steps: instead of bisecting, walk down the grid from its largest step until the error "
                  "against the beam stops falling (two stable steps in a row that lower it by at most a tenth of a "
                  "tolerance) or the range ends: an error-against-cost front's ladder");
  suite->add_flag("--keep-series", o.keep_series,
                  "with --find-steps: keep every probe's series.csv.gz (default: its summary and events only)");
  suite->add_option("--step-range", o.step_range, "with --find-steps: MIN,MAX step searched [s]")
      ->capture_default_str();
  suite->add_option("--tolerance", o.tolerances,
                    "with --find-steps: metric=value,... for frame1_sensor_peak (relative, default 0.10), "
                    "contact_duration (relative, 0.10), impacts_per_cycle (absolute, 0.10); the verdicts' tolerances, "
                    "so they judge the probes' verdicts too");
  suite->add_option("--shard", o.shard,
                    "K/N: run shard K of N (1 <= K <= N): every N-th engine job (with --find-steps: step search) "
                    "in planned order, and the references they need; join the shards with 'merge'");
  return {suite, [options] { return command_suite(options->first, options->second); }};
}

}  // namespace cli
