// The suite runner: the matrix scenarios x laws x engines x time steps, each job in its own process so
// that a crash, an abort or a hang inside an engine's library costs that job alone. Results are
// appended as each job ends (DIR/runs.csv, DIR/runs.jsonl, DIR/runs/<job id>/), so nothing finished is
// lost; --resume skips the jobs already recorded. The reference run of each scenario and law is
// computed once and reused for every engine's errors.
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
#include "harness/suite/step_search.h"
#include "model/simulator.h"

namespace ib {

// The matrix (matrix_settings.h: engines, laws, paths, steps, options, rate, workers, folder, measurement) of a
// suite, with what a suite adds.
struct SuiteSettings : MatrixSettings {
  SuiteSettings() { laws = {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}; }
  std::vector<std::string> inputs;  // scenario files or folders (searched recursively)
  double max_duration_s = 0;        // > 0: runs longer scenarios for this long only (window kept)
  bool extend = false;  // --extend: add a suite with other settings to a folder that holds one (DIR/suite.jsonl)
  // Set: instead of fixed time steps, each (scenario, law, engine, options) group searches its largest
  // stable and accurate steps by bisection (step_search.h) and appends a row to DIR/steps.csv and
  // DIR/steps.jsonl when its search ends. time_steps_s is then ignored for the engines.
  std::optional<StepSearchSettings> step_search;
  bool keep_probe_series = false;  // the probes' series.csv.gz (default: summary and events only)
  // Set: each engine runs in its authors' recommended configuration for each law (its descriptor.json's
  // "recommended": options and time step) instead of contact_paths x time_steps_s; an engine without one
  // runs nothing in this suite. The per-engine options (engine_options) still apply beneath it.
  bool recommended = false;
  // The reference alone on the K-link chain for each K here, for every scenario, law and reference start, scored
  // against the beam: the chain's own error at each resolution (the model's share of an engine's error).
  std::vector<int> reference_chain_links;
  // Set: reference runs are shared with other output folders through this one (harness/jobs/reference_cache.h):
  // a reference whose key is there is copied, not solved; one solved here is stored there.
  std::string reference_cache;
  // An ensemble (docs/results.md, "Ensembles"): every engine configuration runs from engine_starts starts and
  // every reference from reference_starts (at least engine_starts: the references' spread measures whether a
  // case needs an ensemble at all); start K displaces frame 1's tip by K x displacement_step_m beyond the
  // scenario's initial displacement, far below anything physical. 1 and 1: single runs, as before.
  struct Ensemble {
    int engine_starts = 1;
    int reference_starts = 1;
    double displacement_step_m = 1e-7;
  } ensemble;
  // shard (set): its plan is recorded in DIR/shard.jsonl; a --resume of a folder holding another shard, or a
  // whole suite, is refused.
};

struct SuiteOutcome {
  int jobs_run = 0;      // in this invocation
  int jobs_skipped = 0;  // already recorded (--resume)
  int not_ok = 0;        // unstable or failed among those run
  int not_ok_recorded =
      0;             // unstable or failed among every result in the folder: a resumed suite's exit code covers them all
  int recorded = 0;  // every result in the folder
  int step_searches = 0;          // groups whose step search ended (a row in steps.csv) in this invocation
  int jobs_total = 0;             // the whole matrix, recorded or not
  int interrupted_by = 0;         // the signal (SIGINT, SIGTERM) that stopped the suite early; 0: it ran to the end
  int jobs_stopped = 0;           // jobs whose process a signal from outside stopped (not recorded: --resume runs them)
  int stopped_by = 0;             // that signal (the last one seen)
  int references_from_cache = 0;  // recorded from --reference-cache, not solved
};

// How it ended, as every campaign's outcome says it (campaign_folder.h: the exit code's one rule).
CampaignEnd end_of(const SuiteOutcome& outcome);

// Runs the suite (or its shard); progress goes to stderr (a bar on a terminal, lines otherwise). SIGINT or SIGTERM
// stops the worker processes, keeps every finished result and returns with interrupted_by set (a
// later --resume runs the rest). Throws OutputError (run_files.h) when a result cannot be written:
// the output folder, a run's folder or files, runs.csv or runs.jsonl; the workers are stopped first.
// Throws std::invalid_argument for a --resume in a folder that holds another shard or a whole suite.
SuiteOutcome run_suite(const SuiteSettings& settings);

// Several suites into one folder as one plan on one pool of workers (a study's [[suite]] and [[search]]
// parts): no part waits for another to end, the costliest ready job starts first. The folder, workers, time
// limit, resume, extend, shard and simulators are the first part's; each part records its own settings line
// (suite.jsonl, as --extend would), and a job that two parts plan runs once (a search's references among them).
SuiteOutcome run_suites(const std::vector<SuiteSettings>& parts);

// A suite's plan as plain data, made without running anything: each unit of work with the units it waits for
// (an engine's run after the references it is compared with, a chain reference after its beam reference),
// in planned order; with a shard (MatrixSettings::shard), that shard's share. Throws std::invalid_argument as
// run_suites does for input it refuses.
struct PlannedUnit {
  enum class Kind { beam_reference, chain_reference, engine, step_search, unrunnable };
  std::string id;
  Kind kind = Kind::engine;
  std::vector<std::string> after;  // the units it waits for
  std::string same_run_as;         // a job scored from another job's run (native contact): that job's id
};
std::vector<PlannedUnit> plan_suites(const std::vector<SuiteSettings>& parts);

// What each part of plan_suites' parts runs, for `study --plan`: the whole plan, no shard. A job two parts plan runs
// once, with the first part's settings, and is counted there alone; a native run that answers for every law is
// one run but a row per law (each law's row is counted: runs.csv holds it), its process once (to_run).
struct PlannedRunWork {
  std::string engine;
  std::map<std::string, std::string> options;
  double time_step_s = 0;  // 0: the engine's default
  double simulated_s = 0;  // the scenario as cut
};
struct PartRuns {
  int runs = 0;                        // the rows the part adds to runs.csv (references, engines, unrunnable jobs)
  int shared = 0;                      // its jobs an earlier part planned: recorded and counted there
  int scored_only = 0;                 // of runs, the rows scored from another law's native run (not run again)
  int step_searches = 0;               // its step searches' groups: their probes are planned as each search goes
  std::vector<PlannedRunWork> to_run;  // the part's runs that run a process, for the cost estimate
};
std::vector<PartRuns> count_part_runs(const std::vector<SuiteSettings>& parts);

// The suites as a source of units for one runner shared with other parts (a study's sweeps): prepare_suites
// checks and records the settings and plans (throwing as run_suites does), run_units runs the jobs, finish
// tells the outcome. The caller installs the InterruptionHandler (worker_process.h).
class SuiteSource : public UnitSource {
 public:
  virtual SuiteOutcome finish() = 0;
};
std::unique_ptr<SuiteSource> prepare_suites(const std::vector<SuiteSettings>& parts);

}  // namespace ib
