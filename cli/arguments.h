// What every command shares: the exit codes, the command line as typed, and the parsing of arguments
// into the libraries' terms (each throws std::invalid_argument naming the option, the value and what
// is allowed; main turns that into exit 2).
#pragma once

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/option_rules.h"
#include "harness/jobs/campaign_folder.h"
#include "harness/jobs/matrix_settings.h"
#include "harness/jobs/run_job.h"
#include "physics/contact_laws.h"

namespace cli {

constexpr int kExitOk = 0, kExitRunNotOk = 1, kExitBadInput = 2, kExitOutputError = 3, kExitIncompleteMerge = 4;
// `compare`'s: something regressed (reports/compare.py; 1 is a move that did not)
constexpr int kExitCompareRegressed = 4;
constexpr int kExitInterrupted = 128;  // + the signal's number, as a shell reports a process it stopped

// A campaign's exit code (a suite's, a sweep's, a study's): 0 every result ok, 1 one not ok, 128 + the signal
// that stopped it (harness/jobs/campaign_folder.h: how it ended).
int exit_code(const ib::CampaignResult& result);

// The command line as typed (main keeps it here first).
extern int g_argc;
extern char** g_argv;

// The command line as typed, with --resume added when missing: what continues an interrupted suite.
std::string resume_command(int argc, char** argv);

// "unknown command 'X'; allowed: ..." when the first argument is neither an option nor one of app's commands
// (CLI11 alone would say "A subcommand is required"); nullopt otherwise.
std::optional<std::string> unknown_command(const CLI::App& app, int argc, char** argv);

std::vector<std::string> split(const std::string& text, char separator);
// The items as one comma-separated option value: what split(text, ',') reads back.
std::string join_list(const std::vector<std::string>& items);
// A comma-separated option's items: none empty ('--engines ""' and 'reference,,mujoco' are refused, naming
// the option, the value and what is allowed).
std::vector<std::string> split_list(const std::string& text, const std::string& option, const std::string& allowed);

// --option pairs of a command that runs one engine: name=value, or engine.name=value naming that engine (the
// syntax of a suite's, accepted everywhere); another engine's name is refused.
std::map<std::string, std::string> parse_engine_options(const std::vector<std::string>& pairs,
                                                        const std::string& engine);

ib::ContactLaw parse_law(const std::string& name);

void require_engine(const std::string& engine);

double parse_positive(const std::string& text, const std::string& option);

// How runs are measured; shared by `run` and `suite`.
struct MeasurementOptions {
  double window_s = -1, sensor_rate_hz = 2048, merge_window_s = 0.002;
  int timed_repeats = 0;  // timed runs after the logged one (0: the logged run's own time is the cost)
  std::string series = "window";
  double series_rate_hz = 0;  // what an engine run's series.csv.gz keeps [Hz]; 0: the output rate
  bool window_given = false;  // --window given other than on a command line (a study file's window_s)
  // with_timing: the command runs simulators (run, suite), so --repeat and --series apply; score measures files only
  void add_to(CLI::App* app, bool with_timing) {
    app_ = app;
    add_shared_option(app, Shared::window, window_s,
                      "scoring window: the last S seconds of the run [s]; default: the scenario's",
                      /*show_default=*/false);
    add_shared_option(app, Shared::sensor_rate, sensor_rate_hz, "accelerometer sample rate for the sensor peak [Hz]");
    add_shared_option(app, Shared::merge_window, merge_window_s, "onsets closer than this are one impact [s]");
    if (with_timing)
      add_shared_option(
          app, Shared::repeat, timed_repeats,
          "timed runs after the logged one, nothing written; their median is the run time (0: the logged run's own)");
    if (with_timing)
      app->add_option("--series", series,
                      "what a run's folder keeps of its series (series.csv.gz): window (the scoring window), all "
                      "(the whole run) or none (a suite's references keep their window)")
          ->capture_default_str();
    if (with_timing)
      add_shared_option(app, Shared::series_rate, series_rate_hz,
                        "the rate an engine run's series.csv.gz keeps, every k-th sample with the peaks between [Hz]; "
                        "0: every output sample (a suite's references always keep every one)");
  }
  // The option values are checked as they are read (option_rules.h); this checks --series and builds.
  ib::Measurement build() const;  // throws std::invalid_argument naming the option, the value and what is allowed

 private:
  const CLI::App* app_ =
      nullptr;  // the command's: whether --window was given at all (any value it has is then checked)
};

// The options `suite` and `sweep` share (SuiteOptions, SweepOptions: commands.h), as typed: which
// configurations run and how. A sweep's default law is hertz alone, a suite's every law (SuiteOptions).
struct MatrixOptions {
  std::string engines = "reference", laws = "hertz", paths, time_steps, out;
  std::vector<std::string> options;  // --option ENGINE.NAME=VALUE, or NAME=VALUE with one engine; repeatable
  double rate_hz = 4096, time_limit_s = 600;
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  std::string shard;  // K/N, empty: the whole suite or sweep
  bool resume = false;
};

// The shared settings from the shared options (`suite`, `sweep` and a study's parts), every value checked
// (std::invalid_argument naming the option, the value and what is allowed): the engines and laws, the
// steps, the contact paths, the engines' options (checked by each engine now, not in every job), the
// folder, the shard and the measurement (--rate at least --sensor-rate); this binary's simulators.
void matrix_settings_from(const MatrixOptions& o, const MeasurementOptions& measurement_options, ib::MatrixSettings& s);

}  // namespace cli
