// The suite's plan as plain data: from the parts (and the engine catalog they carry) to the jobs, the
// references each job is compared with, the step searches' groups and what cannot run. It is made before
// anything is written or runs (plan_suite, suite_plan.cpp) and tested without processes; the runner
// (suite_runner.h) takes it and runs it. Internal to the harness (suite.h is the interface).
#pragma once

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/jobs/progress.h"
#include "harness/jobs/run_job.h"
#include "harness/jobs/shard_plan.h"
#include "harness/suite/step_search.h"
#include "harness/suite/suite.h"
#include "model/scenario.h"

namespace ib::suite_internal {

enum class JobKind { beam_reference, chain_reference, engine };

struct PlannedJob {
  std::string id;
  JobKind kind = JobKind::engine;
  std::size_t scenario = 0;  // index into SuitePlan::scenarios
  JobSpec spec;
  std::string beam_reference;  // job ids of the references this job is compared with ("" if none)
  std::string chain_reference;
  int chain_links = 0;
  bool step_probe = false;  // a probe of a step search (its series is kept only on request)
  // The job whose run this one scores against its own law's references (native contact ignores the
  // law): it is recorded by that job's process, never run itself. "" for a job that runs.
  std::string same_run_as;
};

// A job that cannot run at all (a malformed scenario, a law the scenario has no parameters for): it
// is recorded as failed with the reason, and the suite goes on.
RunRecord unrunnable(const std::string& id, const std::string& scenario, const std::string& file,
                     const std::string& engine, const std::string& law, const std::string& reason);

// The (options, time step [s]; 0: the engine's default) an engine runs for one law in a suite part: the part's
// contact paths x time steps (a step search: one each, its steps searched), or, with `recommended`, the
// engine's authors' configuration for the law (its descriptor's), none for an engine without one.
// suite_configurations.cpp.
using EngineConfiguration = std::pair<std::map<std::string, std::string>, double>;
std::vector<EngineConfiguration> engine_configurations(const SuiteSettings& part, const SimulatorCatalog& catalog,
                                                       const std::string& engine, ContactLaw law,
                                                       const std::map<std::string, std::string>& engine_options);

// The step search judges "within tolerance" with the verdicts' own tolerances: one record.
SuiteSettings with_one_tolerance_record(SuiteSettings settings);
std::vector<SuiteSettings> with_one_tolerance_record(const std::vector<SuiteSettings>& parts);

struct SuitePlan {
  // Copies, the tolerance record set in them (with_one_tolerance_record). What every part shares (the folder,
  // the workers, the time limit, resume, shards) is the first part's; what decides a job's run (its scenario
  // as cut, its measurement, its step search) is its own part's.
  std::vector<SuiteSettings> parts;
  std::vector<Scenario> scenarios;                   // as loaded and cut for their part
  std::vector<std::size_t> scenario_part;            // the part each scenario was loaded (and cut) for
  std::vector<std::vector<std::string>> part_jobs;   // each part's job ids, also those an earlier part planned
  std::vector<std::vector<std::string>> part_files;  // each part's scenario files, readable or not
  std::vector<PlannedJob> jobs;                      // the references and engine runs, in planned order
  std::vector<PlannedJob> step_groups;               // step searches: one job (dt = 0) per group, not run itself
  // The references some run of the whole plan is compared with: a reference's series is kept only then (an
  // ensemble's reference starts beyond its engines' measure the references' spread by their metrics alone).
  std::set<std::string> compared_references;
  std::vector<RunRecord> unrunnable;  // one record each, in planned order
  // A shard's plan (shard_of): the digest of the whole suite's plan and settings, the same in every shard of it
  // (shard.jsonl: merge tells shards of one suite from those of another); "" for a whole suite.
  std::string whole_suite_digest;
  // Made for `study --plan`'s counts (count_part_runs): the warnings go into the jobs' records, not to stderr.
  bool quiet = false;

  const SuiteSettings& shared() const { return parts.front(); }
  // The part a job belongs to: that of its scenario, as loaded and cut for that part.
  const SuiteSettings& part_of(const PlannedJob& job) const { return parts[scenario_part[job.scenario]]; }
};

// The parts' plan: their scenario files read and cut, the job matrix scenarios x laws x engines x steps x
// ensemble starts, and the references each job is compared with. A job two parts plan is planned once, with
// the first part's settings. Throws std::invalid_argument for what no run can fix (a missing file, two
// scenarios of one name, a run too large or a window outside it); a file that cannot be read as a scenario is
// planned as unrunnable instead, and the others run. quiet: a window in the start-up transient is recorded with
// the jobs' warnings but not said on stderr (`study --plan`'s counts: the run says it).
SuitePlan plan_suite(const std::vector<SuiteSettings>& parts, bool quiet = false);

// A job of the plan's scenario `scenario`, its id made from what decides its run.
PlannedJob make_job(const SuitePlan& plan, std::size_t scenario, JobKind kind, const std::string& engine,
                    ContactLaw law, double dt, const std::map<std::string, std::string>& options, int start = 0);

// The row a step-search group writes to steps.csv (its probes' job ids are the group's id with /dt=...).
StepGroup step_group(const SuitePlan& plan, const PlannedJob& job);

// A job's work for the remaining-time estimate and the choice of what runs first: its steps (an engine at a
// given step), else its simulated seconds; jobs of one engine and options cost about the same per unit.
JobWork work_of(const SuitePlan& plan, const PlannedJob& job);

// The plan as units of work and what each waits for (plan_suites).
std::vector<PlannedUnit> planned_units(const SuitePlan& plan);

// What the suite records, in planned order: its job ids (the unrunnable first), and the keys of its step
// searches' rows (suite_shard.cpp).
std::vector<std::string> planned_job_ids(const SuitePlan& plan);
std::vector<std::string> planned_step_keys(const SuitePlan& plan);

// --shard K/N: the share of the whole plan one shard runs: every N-th unit of work in planned order (the
// unrunnable jobs, then the step-search groups, then the engine jobs; the references when there is nothing
// else), with the references those units are compared with; whole_suite_digest set (suite_shard.cpp).
SuitePlan shard_of(SuitePlan whole, const Shard& shard);

// The plan a suite runs: plan_suite's, then shard_of's share when the parts name a shard (suite_shard.cpp).
SuitePlan plan_to_run(const std::vector<SuiteSettings>& parts);

// A part's settings record (DIR/suite.jsonl, suite_settings.cpp): what decides its results, its scenario files
// with their contents' digests.
nlohmann::ordered_json settings_record(const SuitePlan& plan, std::size_t part);

}  // namespace ib::suite_internal
