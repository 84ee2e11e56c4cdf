// One function per command (cli/command_<name>.cpp), wired to its options in main.cpp. Each returns
// its exit code (arguments.h) and throws for bad input or a write error, which main turns into exit 2 or 3.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "harness/suite/suite.h"
#include "harness/sweep/sweep.h"

namespace cli {

// `suite`'s options: the shared ones (MatrixOptions, arguments.h) and its own.
struct SuiteOptions : MatrixOptions {
  SuiteOptions() { laws = "hertz,viscoelastic,newton"; }
  std::vector<std::string> inputs;
  double max_duration_s = 0;  // 0: not given (given: > 0)
  bool extend = false;
  bool find_steps = false, keep_series = false;
  bool recommended = false;  // --recommended: each engine in its authors' configuration per law
  int steps_per_octave = 4;
  bool step_walk = false;  // --step-walk: the search walks down the grid (a front's ladder) instead of bisecting
  std::string step_range = "1e-6,1e-3", tolerances;
  std::string reference_cache;        // a folder sharing reference runs between output folders
  int ensemble_starts = 1;            // --ensemble: starts of every configuration
  int reference_ensemble_starts = 0;  // --reference-ensemble: the references' starts; 0: --ensemble's
  double ensemble_step_m = 1e-7;      // --ensemble-step: frame 1's tip displacement between starts [m]
  std::string reference_chains;       // --reference-chains K,K,...: the reference alone on K-link chains
};

// `sweep`'s options: the shared ones (MatrixOptions, arguments.h) and its own.
struct SweepOptions : MatrixOptions {
  std::string scenario, ratios = "0.85:1.25:0.01", start = "both";
  double duration_s = 60, rest_duration_s = -1, window_s = 10;
  // the reference's ensemble of starts from rest (SweepSettings::ensemble): 1, no ensemble; ratios "": every ratio
  int reference_ensemble_starts = 1;
  double ensemble_step_m = 1e-7;
  std::string ensemble_ratios;
};

int command_run(const std::string& path, const std::string& engine, const std::string& law_name, const std::string& out,
                double rate_hz, double series_start_s, double time_step_s, const std::vector<std::string>& option_pairs,
                const MeasurementOptions& measurement_options, double time_limit_s, double max_duration_s,
                double start_offset_m);  // max_duration_s: 0, the scenario's whole run

int command_modes(const std::string& path, bool json, const std::vector<std::string>& option_pairs);

int command_suite(const SuiteOptions& o, const MeasurementOptions& measurement_options);
// The suite's settings from its options, every value checked (std::invalid_argument naming the option, the
// value and what is allowed): what `suite` and a study's [[suite]] and [[search]] parts share.
ib::SuiteSettings suite_settings_from(const SuiteOptions& o, const MeasurementOptions& measurement_options);
// What a suite's outcome means for the exit code, said on stdout (or stderr when it stopped early).
int suite_exit_code(const ib::SuiteSettings& s, const ib::SuiteOutcome& outcome);
// Appends the command that writes into OUT, when it started and the verdicts' tolerances to OUT/commands.jsonl
// (the report names the commands that produced its folder); note: which part of a study, "" for none.
void record_command(const std::string& out, const ib::VerdictSettings& verdicts, const std::string& note);

// The model an engine builds for a run, in the engine's own format, for a person to open in the
// engine's tools (MuJoCo: MJCF for its viewer; the reference: its modal model as JSON).
int command_export(const std::string& path, const std::string& engine, const std::string& law_name,
                   const std::string& out, double time_step_s, double rate_hz,
                   const std::vector<std::string>& option_pairs);

// A run made elsewhere (series.csv and events.csv in the harness's format, run_files.h), measured with the
// harness's own metric code exactly as every simulator's run is; with a reference folder, its errors
// against it too (the vs_reference_* figures of runs.csv).
int command_score(const std::string& folder, const std::string& scenario_path, const std::string& reference_folder,
                  bool json, const MeasurementOptions& measurement_options);

// The report is made by reports/make_report.py with Debian's matplotlib (python3-matplotlib), from
// the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out);

// The shards' folders joined into one suite folder (harness/study/merge.h), then its report, made as `report` makes it.
int command_merge(const std::string& out, const std::vector<std::string>& shards, bool no_report);

int command_list(const std::string& folder);

// Every simulator of this build with its descriptor; json: the text of a result folder's engines.json;
// names: the names alone, comma-separated (what --engines takes).
int command_engines(bool json, bool names);

// `sweep` (harness/sweep/sweep.h): its options are registered by add_sweep_command, which sets `command`.
void add_sweep_command(CLI::App& app, SweepOptions& options, MeasurementOptions& measurement, CLI::App*& command);
int command_sweep(const SweepOptions& options, const MeasurementOptions& measurement_options);
ib::SweepSettings sweep_settings_from(const SweepOptions& o, const MeasurementOptions& measurement_options);
int sweep_exit_code(const ib::SweepSettings& s, const ib::SweepOutcome& outcome);

// `study FILE --out DIR`: every part of a study file (study_file.h) into one folder, then its report.
struct StudyOptions {
  std::string file, out, shard;
  std::string skip;             // kinds of parts left out, comma-separated: suite, search, sweep
  std::string reference_cache;  // a folder sharing reference runs between output folders
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  bool resume = false, no_report = false;
  bool plan = false;  // --plan: check the file and say what each part runs, run nothing
};
int command_study(const StudyOptions& options);

// `repro RUN_FOLDER OUT`: one run of a result folder made ready to run alone and to file with an engine's
// authors: OUT/scenario.toml (the scenario it ran), OUT/repro.sh (the one command that reruns it, with its
// engine, law, step, options, start and length), OUT/repro.json (what it was: job, verdict, reason, engine
// version, the folder it came from) and, where the engine exports one, its model (MuJoCo: OUT/model.xml).
// scenario_path: the scenario file where the run's own record names one that is no longer there.
int command_repro(const std::string& run_folder, const std::string& out, const std::string& scenario_path);

// `compare BASE NEW [MORE ...]`: result folders side by side, made by reports/compare.py (docs/compare.md):
// what differs between what made them, then what moved beyond the noise; with more than two, each folder
// against the next (a history). Its exit code: 0 nothing moved, 1 something moved, 2 bad input.
struct CompareOptions {
  std::vector<std::string> folders;  // the baseline first, each next one judged against the one before
  std::string json, markdown, html;  // files to write (html: a folder), none when empty
  bool cost_across_machines = false;
  double cost_noise = 0.3;  // the least relative change of CPU time told apart from a shared machine's drift
};
int command_compare(const CompareOptions& options);

}  // namespace cli
