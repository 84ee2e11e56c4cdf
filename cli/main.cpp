// impactbench: the command line. Exit codes:
//   0    every run ok (or inaccurate)
//   1    some run unstable or failed (its files and reason are still written)
//   2    bad usage or input (the message names the file, line, key or option, the value and what is allowed)
//   3    a result could not be written (full disk, unwritable folder): the message names the file, the
//        OS's reason and what to do; everything recorded before it is kept, and `suite --resume` goes on
//   4    `merge` joined what exists, but a shard lacks results (a failed array task): the message names the
//        shard, what it lacks and the command that finishes it
//   130  `suite` stopped by SIGINT (143: SIGTERM), every finished result kept; the message says how to resume
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

int main(int argc, char** argv) {
  using namespace cli;
  g_argc = argc;
  g_argv = argv;
  CLI::App app{"impactbench: a benchmark of physics engines on a two-frame vibro-impact rig"};
  app.require_subcommand(1);

  std::string scenario_path, engine = "reference", law = "hertz", out_dir,
                             list_folder = std::string(IMPACTBENCH_SCENARIO_DIR);
  bool json = false;
  double rate_hz = 4096, series_start_s = -1, time_step_s = 0, run_time_limit_s = 600, run_duration_s = 0;
  std::vector<std::string> options;
  MeasurementOptions run_measurement, suite_measurement;
  SuiteOptions suite_options;

  CLI::App* modes = app.add_subcommand("modes", "each frame's natural frequencies [Hz] and tip modal values");
  modes->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  modes->add_flag("--json", json, "print JSON");
  modes->add_option("--option", options, "reference option name=value (modes=beam|beam_paper|chain, n=N, links=K)");

  CLI::App* run = app.add_subcommand(
      "run", "run one scenario with one engine and law; write DIR/summary.json, series.csv, events.csv");
  run->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  run->add_option("--engine", engine, "simulator (see 'impactbench list')")->capture_default_str();
  run->add_option("--law", law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  run->add_option("--out", out_dir, "output folder")->required();
  add_shared_option(run, Shared::rate, rate_hz, "output series sample rate [Hz]");
  add_shared_option(run, Shared::series_start, series_start_s,
                    "first output sample [s]; default: start of the scoring window", false);
  add_shared_option(run, Shared::dt, time_step_s, "time step of fixed-step engines [s]; default: each engine's", false);
  add_shared_option(run, Shared::duration, run_duration_s,
                    "run a scenario longer than this for this long only, keeping its scoring window [s]", false);
  run->add_option("--option", options, "simulator option name=value, repeatable (see 'impactbench list')");
  double run_start_offset_m = 0;
  run->add_option("--start-offset", run_start_offset_m,
                  "frame 1's initial tip displacement beyond the scenario's, as an ensemble's start [m]")
      ->check(CLI::Range(-0.01, 0.01));
  run_measurement.add_to(run, /*with_timing=*/true);
  add_shared_option(run, Shared::time_limit, run_time_limit_s,
                    "the run (its references included) is stopped past this and recorded as failed [s]");

  CLI::App* suite = app.add_subcommand("suite",
                                       "run scenarios x laws x engines x time steps in worker processes; "
                                       "append DIR/runs.csv, DIR/runs.jsonl and DIR/runs/<job>/");
  suite->add_option("scenarios", suite_options.inputs, "scenario files or folders; default: the published scenarios");
  suite->add_option("--engines", suite_options.engines, "comma-separated engines")->capture_default_str();
  suite->add_option("--laws", suite_options.laws, "comma-separated laws")->capture_default_str();
  add_shared_list_option(suite, Shared::dt, suite_options.time_steps,
                         "comma-separated time steps of fixed-step engines [s]");
  suite->add_option("--paths", suite_options.paths,
                    "comma-separated contact paths of the engines: matched, injected, native; default: each engine's");
  add_shared_option(suite, Shared::jobs, suite_options.jobs, "worker processes");
  suite->add_option("--out", suite_options.out, "output folder")->required();
  suite->add_flag("--resume", suite_options.resume,
                  "continue the suite recorded in the output folder (same settings): skip the jobs already recorded");
  suite->add_flag("--extend", suite_options.extend,
                  "add this suite to a folder that holds suites with other settings (a study's parts); a job it shares "
                  "with the folder must have been recorded with the same settings");
  add_shared_option(suite, Shared::time_limit, suite_options.time_limit_s,
                    "per job; a job past it is stopped and recorded [s]");
  add_shared_option(suite, Shared::rate, suite_options.rate_hz, "output series sample rate [Hz]");
  add_shared_option(suite, Shared::duration, suite_options.max_duration_s,
                    "run scenarios longer than this for this long only, keeping their scoring window [s]", false);
  suite->add_option("--option", suite_options.options, "engine.name=value, repeatable (e.g. reference.n=5)");
  suite->add_option("--reference-cache", suite_options.reference_cache,
                    "a folder that shares reference runs between output folders: a reference it holds (same scenario "
                    "content, settings and executable) is copied, not solved; one solved is stored there");
  suite
      ->add_option("--ensemble", suite_options.ensemble_starts,
                   "N: run every configuration from N starts, start K with frame 1's tip displaced by K x "
                   "--ensemble-step; the report gives each metric and error with its confidence interval")
      ->capture_default_str();
  suite
      ->add_option("--reference-ensemble", suite_options.reference_ensemble_starts,
                   "N: the references' starts (at least --ensemble; 0: --ensemble's): their spread says whether a "
                   "case needs an ensemble")
      ->capture_default_str();
  suite->add_option("--reference-chains", suite_options.reference_chains,
                    "K,K,...: the reference alone on the K-link chain of every scenario, law and reference start, "
                    "scored against the beam: how the chain's resolution alone moves each metric (1 <= K <= 64)");
  suite
      ->add_option("--ensemble-step", suite_options.ensemble_step_m,
                   "frame 1's initial tip displacement between two starts of an ensemble [m]")
      ->capture_default_str();
  suite_measurement.add_to(suite, /*with_timing=*/true);
  suite->add_flag("--recommended", suite_options.recommended,
                  "each engine in its authors' recommended configuration for each law: the options and time step of "
                  "its adapters/<engine>/descriptor.json, every setting with its source (docs/engines.md); not with "
                  "--paths, --dt or --find-steps");
  suite->add_flag(
      "--find-steps", suite_options.find_steps,
      "per scenario, law, engine and options: search the largest stable step and the largest step at "
      "which each headline metric is within tolerance, by bisection on a geometric grid (--steps-per-octave); "
      "writes DIR/steps.csv and DIR/steps.jsonl");
  suite
      ->add_option(
          "--steps-per-octave", suite_options.steps_per_octave,
          "with --find-steps: grid steps per halving of the step (4: a ratio of 1.19; 1: a coarse search, ratio 2)")
      ->capture_default_str();
  suite->add_flag("--step-walk", suite_options.step_walk,
                  "with --find-steps: instead of bisecting, walk down the grid from its largest step until the error "
                  "against the beam stops falling (two stable steps in a row that lower it by at most a tenth of a "
                  "tolerance) or the range ends: an error-against-cost front's ladder");
  suite->add_flag("--keep-series", suite_options.keep_series,
                  "with --find-steps: keep every probe's series.csv.gz (default: its summary and events only)");
  suite->add_option("--step-range", suite_options.step_range, "with --find-steps: MIN,MAX step searched [s]")
      ->capture_default_str();
  suite->add_option("--tolerance", suite_options.tolerances,
                    "with --find-steps: metric=value,... for frame1_sensor_peak (relative, default 0.10), "
                    "contact_duration (relative, 0.10), impacts_per_cycle (absolute, 0.10); the verdicts' tolerances, "
                    "so they judge the probes' verdicts too");
  suite->add_option("--shard", suite_options.shard,
                    "K/N: run shard K of N (1 <= K <= N): every N-th engine job (with --find-steps: step search) "
                    "in planned order, and the references they need; join the shards with 'merge'");

  std::string merge_out;
  std::vector<std::string> merge_inputs;
  bool merge_no_report = false;
  CLI::App* merge = app.add_subcommand("merge",
                                       "join the folders of a suite's shards (suite --shard K/N) into one "
                                       "suite folder, then make its report");
  merge->add_option("out", merge_out, "a new or empty folder for the joined suite")->required();
  merge->add_option("shards", merge_inputs, "the shards' folders")->required();
  merge->add_flag("--no-report", merge_no_report, "join only; make the report later with 'report OUT'");

  // default: the build's first engine (the catalog's order: adapters/CMakeLists.txt), the reference when it has none
  const std::vector<std::string> simulators = ib::simulator_names();
  std::string export_engine = simulators.size() > 1 ? simulators[1] : simulators.front(), export_out;
  CLI::App* export_model =
      app.add_subcommand("export",
                         "write the model a simulator builds for a scenario, in its own format "
                         "(an engine's for its viewer, e.g. MJCF; reference: its modal model as JSON)");
  export_model->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  export_model->add_option("--engine", export_engine, "engine (engines --names)")->capture_default_str();
  export_model->add_option("--law", law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  add_shared_option(export_model, Shared::dt, time_step_s, "time step [s]; default: the engine's", false);
  export_model->add_option("--option", options, "engine option name=value, repeatable");
  export_model->add_option("--out", export_out, "output file; default: standard output");
  double export_rate_hz = 4096;
  add_shared_option(export_model, Shared::rate, export_rate_hz,
                    "reference: output sample rate of the run the model is for [Hz]");

  std::string score_folder, score_scenario, score_reference;
  MeasurementOptions score_measurement;
  CLI::App* score = app.add_subcommand("score",
                                       "measure a run folder's series.csv and events.csv (from any solver) with "
                                       "the harness's metrics; print them with the names of runs.csv");
  score->add_option("run", score_folder, "folder with series.csv and events.csv in the harness's format")->required();
  score->add_option("--scenario", score_scenario, "the scenario file (.toml) the run was made for")->required();
  score->add_option("--reference", score_reference, "a run folder to compare with (adds the vs_reference_* figures)");
  score->add_flag("--json", json, "print JSON (NaN as null)");
  score_measurement.add_to(score, /*with_timing=*/false);

  std::string report_folder, report_out;
  CLI::App* report =
      app.add_subcommand("report", "make the report (index.html, summary.md, figures) from a suite's saved results");
  report->add_option("suite", report_folder, "a suite's output folder")->required();
  report->add_option("--out", report_out, "report folder; default: SUITE/report");

  std::string repro_folder, repro_out, repro_scenario;
  CLI::App* repro =
      app.add_subcommand("repro",
                         "make one run of a result folder ready to rerun alone and to file: its "
                         "scenario, the one command that reruns it, its model where the engine exports one");
  repro->add_option("run", repro_folder, "the run's folder (SUITE/runs/<job id>, or a run's --out)")->required();
  repro->add_option("out", repro_out, "the folder to write")->required();
  repro->add_option("--scenario", repro_scenario, "the scenario file, where the one the run names is no longer there");

  CompareOptions compare_options;
  CLI::App* compare = app.add_subcommand("compare",
                                         "put two result folders side by side: what differs between what made "
                                         "them, then what moved beyond the noise (exit 1 when something did)");
  compare
      ->add_option("folders", compare_options.folders,
                   "BASE NEW: the baseline result folder (a suite's or a study's) and the one judged against it; "
                   "or several in order, each judged against the one before")
      ->required()
      ->expected(2, -1);
  compare->add_option("--json", compare_options.json, "write the comparison as JSON to this file");
  compare->add_option("--markdown", compare_options.markdown, "write the comparison as Markdown to this file");
  compare->add_option("--html", compare_options.html,
                      "write compare.html (a figure per moved configuration) and compare.md into this folder");
  compare->add_flag("--cost-across-machines", compare_options.cost_across_machines,
                    "judge CPU costs timed on other machines too (not comparable by default)");
  compare
      ->add_option("--cost-noise", compare_options.cost_noise,
                   "the least relative change of CPU time told apart from the machine's drift between identical runs")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();

  SweepOptions sweep_options;
  MeasurementOptions sweep_measurement;
  sweep_measurement.series = "none";  // a sweep's tables and Poincare samples are its results
  CLI::App* sweep = nullptr;
  add_sweep_command(app, sweep_options, sweep_measurement, sweep);

  StudyOptions study_options;
  CLI::App* study = app.add_subcommand("study",
                                       "run a study file's suites, step searches and sweeps into one folder, "
                                       "then make its report (docs/studies.md, \"Study files\")");
  study->add_option("file", study_options.file, "a study file (.toml), e.g. studies/default.toml")->required();
  study->add_option("--out", study_options.out, "output folder (required unless --plan)");
  study->add_option("--jobs", study_options.jobs, "worker processes")->capture_default_str();
  study->add_option("--shard", study_options.shard,
                    "K/N: every part's K-th of N shares, for a job array (merge joins them)");
  study->add_flag("--resume", study_options.resume, "continue the study recorded in --out");
  study->add_option("--reference-cache", study_options.reference_cache,
                    "a folder that shares reference runs between output folders (as suite --reference-cache)");
  study->add_option("--skip", study_options.skip, "kinds of parts left out, comma-separated: suite, search, sweep");
  study->add_flag("--no-report", study_options.no_report, "leave the report out");
  study->add_flag("--plan", study_options.plan, "check the file and print what each part runs; run nothing");

  bool engines_json = false, engines_names = false;
  CLI::App* engines = app.add_subcommand(
      "engines", "every simulator of this build: name, version, Debian packages, report colours, diagnostics keys");
  engines->add_flag("--json", engines_json, "print the descriptors as JSON (what a suite writes to DIR/engines.json)");
  engines->add_flag("--names", engines_names, "print the simulators' names alone, comma-separated (for --engines)")
      ->excludes("--json");

  CLI::App* list = app.add_subcommand("list", "the scenarios, engines, laws and simulator options of this build");
  list->add_option("folder", list_folder, "scenario folder")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const std::invalid_argument& error) {  // a shared option's value, checked as it is read (option_rules.h)
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
  try {
    if (modes->parsed()) return command_modes(scenario_path, json, options);
    if (run->parsed())
      return command_run(scenario_path, engine, law, out_dir, rate_hz, series_start_s, time_step_s, options,
                         run_measurement, run_time_limit_s, run_duration_s, run_start_offset_m);
    if (suite->parsed()) return command_suite(suite_options, suite_measurement);
    if (sweep->parsed()) return command_sweep(sweep_options, sweep_measurement);
    if (study->parsed()) return command_study(study_options);
    if (report->parsed()) return command_report(report_folder, report_out);
    if (compare->parsed()) return command_compare(compare_options);
    if (repro->parsed()) return command_repro(repro_folder, repro_out, repro_scenario);
    if (merge->parsed()) return command_merge(merge_out, merge_inputs, merge_no_report);
    if (export_model->parsed())
      return command_export(scenario_path, export_engine, law, export_out, time_step_s, export_rate_hz, options);
    if (score->parsed()) return command_score(score_folder, score_scenario, score_reference, json, score_measurement);
    if (engines->parsed()) return command_engines(engines_json, engines_names);
    return command_list(list_folder);
  } catch (const ib::OutputError& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitOutputError;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
}
