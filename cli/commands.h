// One file per command (cli/command_<name>.cpp): its options, registered by its add_<name>_command, and the
// function that runs it. main.cpp only dispatches. Each returns its exit code (arguments.h) and throws for bad
// input or a write error, which main turns into exit 2 or 3.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "harness/suite/suite.h"
#include "harness/sweep/sweep.h"

namespace cli {

// A command as main sees it: its subcommand of the application, and what runs it once that was parsed (the
// options it reads live as long as the function).
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
Command add_modes_command(CLI::App& app);
Command add_run_command(CLI::App& app);
Command add_suite_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_export_command(CLI::App& app);
Command add_score_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_repro_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_sweep_command(CLI::App& app);
Command add_study_command(CLI::App& app);
Command add_engines_command(CLI::App& app);
Command add_metrics_command(CLI::App& app);
Command add_list_command(CLI::App& app);

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

// The suite's settings from its options, every value checked (std::invalid_argument naming the option, the
// value and what is allowed): what `suite` and a study's [[suite]] and [[search]] parts share.
ib::SuiteSettings suite_settings_from(const SuiteOptions& o, const MeasurementOptions& measurement_options);
// What a suite's outcome means for the exit code, said on stdout (or stderr when it stopped early).
int suite_exit_code(const ib::SuiteSettings& s, const ib::SuiteOutcome& outcome);
// Appends the command that writes into OUT, when it started and the verdicts' tolerances to OUT/commands.jsonl
// (the report names the commands that produced its folder); note: which part of a study, "" for none.
void record_command(const std::string& out, const ib::VerdictSettings& verdicts, const std::string& note);

// The report of a result folder (`report`, and `merge` and `study` after their runs), made by
// reports/make_report.py with Debian's matplotlib (python3-matplotlib), from the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out);

// The sweep's settings from its options, every value checked (as suite_settings_from), and what its outcome
// means for the exit code: what `sweep` and a study's [[sweep]] parts share.
ib::SweepSettings sweep_settings_from(const SweepOptions& o, const MeasurementOptions& measurement_options);
int sweep_exit_code(const ib::SweepSettings& s, const ib::SweepOutcome& outcome);

}  // namespace cli
