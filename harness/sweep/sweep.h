// A frequency sweep (docs/sweeps.md): the motor speed ratio r = f_motor / f_1 stepped over a range, each
// simulator's steady response measured at every ratio, started from rest at each ratio or continued from
// the previous ratio's final state, sweeping up and down (an impacting oscillator's branches coexist).
//
// The unit of work is a chain: one configuration (engine, law, contact path, step, options) and start,
// its ratios in order (a start from rest: one ratio). A chain runs in its own process (a crash costs that
// chain alone) and writes each ratio's results as the ratio ends, in DIR/runs/<row id>/ (summary.json,
// events.csv, row.json, poincare.csv, state.txt); DIR/sweep.jsonl, sweep.csv and poincare.csv are made from
// those folders in planned order whenever a ratio ends, so they hold one row per ratio and are the same
// however the sweep was interrupted, resumed or divided into shards (--shard K/N: every N-th chain).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/jobs/campaign_folder.h"
#include "harness/jobs/matrix_settings.h"
#include "harness/jobs/run_job.h"
#include "harness/jobs/shard_plan.h"
#include "harness/jobs/unit_source.h"
#include "model/simulator.h"

namespace ib {

enum class SweepStart { rest, up, down };
const char* to_string(SweepStart start);

// FROM:TO:STEP as --ratios takes it: FROM, FROM + STEP, ... up to TO (within STEP / 1000), rounded to
// 1e-9; throws std::invalid_argument naming --ratios, the value and what is allowed.
std::vector<double> parse_ratios(const std::string& text);

// The matrix (matrix_settings.h: engines, laws, paths, steps, options, rate, workers, folder, measurement) of a
// sweep, with what a sweep adds; a sweep's default law is hertz alone, its time limit per ratio.
struct SweepSettings : MatrixSettings {
  std::string scenario_path;   // a scenario with a motor
  std::vector<double> ratios;  // ascending
  std::vector<SweepStart> starts = {SweepStart::rest};
  // Each ratio's run length [s], rounded to whole motor periods: a continuation's ratios after its first
  // (default 60 s: docs/sweeps.md); a start from rest, and a continuation's first ratio (from rest), run the scenario's
  // own duration unless rest_duration_s is set.
  double continuation_duration_s = 60;
  std::optional<double> rest_duration_s;
  double window_s = 10;  // the last window_s of each run is scored [s] (whole periods)
  // An ensemble of the reference's starts from rest (docs/sweeps.md, "Multistable ratios"): at each of `ratios`
  // (empty: every ratio of the sweep) the reference also runs from starts K = 1 .. reference_starts - 1, frame 1's
  // tip displaced by K x displacement_step_m beyond the scenario's initial displacement (start 0 is the row from
  // rest itself). Near the edges of the impacting region the start-up transient is chaotic, so which attractor
  // one start reaches is chance: the fraction of starts reaching each regime is the fact, and a ratio whose
  // starts reach more than one regime is multistable. Engines run from one start (their cost is the budget's).
  struct StartEnsemble {
    int reference_starts = 1;  // 1: no ensemble
    double displacement_step_m = 1e-7;
    std::vector<double> ratios;  // each one of the sweep's ratios
  } ensemble;
};

struct SweepOutcome {
  int rows_run = 0, rows_skipped = 0, rows_total = 0;
  int not_ok = 0;          // rows whose verdict is not ok among all recorded
  int interrupted_by = 0;  // SIGINT or SIGTERM that stopped the sweep; 0: it ran to its end
  int chains_stopped = 0;  // chains whose process a signal from outside stopped (--resume runs the rest)
  int stopped_by = 0;      // that signal (the last one seen)
};

// How it ended, as every campaign's outcome says it (campaign_folder.h: the exit code's one rule).
CampaignEnd end_of(const SweepOutcome& outcome);

// Runs the sweep (or its shard); progress on stderr. Throws std::invalid_argument for bad input (a
// scenario without a motor, a --resume of a folder holding another sweep or shard) before running
// anything, OutputError (run_files.h) when a result cannot be written.
SweepOutcome run_sweep(const SweepSettings& settings);

// The sweep as a source of units for one runner shared with other parts (a study): prepare_sweep checks the
// settings and prepares the folder (throwing as run_sweep does), run_units runs its chains, finish writes the
// tables and tells the outcome. The caller installs the InterruptionHandler (worker_process.h).
class SweepSource : public UnitSource {
 public:
  virtual SweepOutcome finish() = 0;
};
std::unique_ptr<SweepSource> prepare_sweep(const SweepSettings& settings);

// ---- The plan, shared by the runner, the merge and the tests.
struct SweepRow {
  std::string id;                       // "<configuration id>/<start>/r=<ratio>": its folder below runs/
  std::string chain;                    // "<configuration id>/<start>" (rest: with /r=<ratio>)
  JobSpec job;                          // scenario file, engine, law, step, options
  SweepStart start = SweepStart::rest;  // an ensemble's start K >= 1 (job.start) is from rest; its id ends in /start=K
  double ratio = 0;
  bool first_of_chain = true;
};
struct SweepChain {
  std::string id;
  std::vector<SweepRow> rows;  // in the order they run (down: descending ratios)
};
// The chains in planned order: configuration (engine, law, path, step), then start, then ratio (a ratio's
// ensemble starts right after its row from rest).
std::vector<SweepChain> plan_sweep(const SweepSettings& settings, const std::string& scenario_name);
std::string ratio_text(double ratio);  // "0.95", as row ids and tables print a ratio
// FROM:TO:STEP ranges, comma-separated ("0.92:0.95:0.01,1.08:1.12:0.01"), as --ensemble-ratios takes them: the
// ratios in ascending order, each one a ratio of `sweep_ratios` (std::invalid_argument naming one that is not).
std::vector<double> parse_ensemble_ratios(const std::string& text, const std::vector<double>& sweep_ratios);

// The tables (sweep.jsonl, sweep.csv, poincare.csv) made again from the row folders of `rows`, in their order, by
// the recorder (jobs/recorder.h); rows without a folder's row.json are left out. Returns the number of rows written.
int write_sweep_tables(const std::string& folder, const std::vector<std::string>& row_ids);

}  // namespace ib
