// One function per command (cli/command_<name>.cpp), wired to its options in main.cpp. Each returns
// its exit code (arguments.h) and throws for bad input or a write error, which main turns into exit 2 or 3.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli/arguments.h"

namespace cli {

struct SuiteOptions {
  std::vector<std::string> inputs;
  std::string engines = "reference", laws = "hertz,viscoelastic,newton", time_steps, paths, out;
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  double time_limit_s = 600, rate_hz = 4096, max_duration_s = 0;
  bool resume = false, extend = false;
  bool duration_given = false;  // --duration was given (0 is then refused, not "no limit")
  std::vector<std::string> options;
  bool find_steps = false, keep_series = false;
  int steps_per_octave = 4;
  std::string step_range = "1e-6,1e-3", tolerances;
  std::string shard;  // K/N, empty: the whole suite
};

struct SweepOptions {
  std::string scenario, ratios = "0.85:1.25:0.01", start = "both", engines = "reference", laws = "hertz", paths, time_steps, out;
  std::vector<std::string> options;
  double duration_s = 60, rest_duration_s = -1, window_s = 10, rate_hz = 4096, time_limit_s = 600;
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  std::string shard;
  bool resume = false;
};

int command_run(const std::string& path, const std::string& engine, const std::string& law_name, const std::string& out,
                double rate_hz, double series_start_s, double time_step_s, const std::vector<std::string>& option_pairs,
                const MeasurementOptions& measurement_options,
                double time_limit_s);

int command_modes(const std::string& path, bool json, const std::vector<std::string>& option_pairs);

int command_suite(const SuiteOptions& o, const MeasurementOptions& measurement_options);

// The model an engine builds for a run, in the engine's own format, for a person to open in the
// engine's tools (MuJoCo: MJCF for its viewer; the reference: its modal model as JSON).
int command_export(const std::string& path, const std::string& engine, const std::string& law_name, const std::string& out,
                   double time_step_s, double rate_hz, const std::vector<std::string>& option_pairs);

// A run made elsewhere (series.csv and events.csv in the harness's format, run_files.h), measured with the
// harness's own metric code exactly as every simulator's run is; with a reference folder, its errors
// against it too (the vs_reference_* figures of runs.csv).
int command_score(const std::string& folder, const std::string& scenario_path, const std::string& reference_folder,
                  bool json, const MeasurementOptions& measurement_options);

// The report is made by reports/make_report.py with Debian's matplotlib (python3-matplotlib), from
// the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out);

// The shards' folders joined into one suite folder (harness/merge.h), then its report, made as `report` makes it.
int command_merge(const std::string& out, const std::vector<std::string>& shards, bool no_report);

int command_list(const std::string& folder);

// Every simulator of this build with its descriptor; json: the text of a result folder's engines.json;
// names: the names alone, comma-separated (what --engines takes).
int command_engines(bool json, bool names);

// `sweep` (harness/sweep.h): its options are registered by add_sweep_command, which sets `command`.
void add_sweep_command(CLI::App& app, SweepOptions& options, MeasurementOptions& measurement, CLI::App*& command);
int command_sweep(const SweepOptions& options, const MeasurementOptions& measurement_options);

}  // namespace cli
