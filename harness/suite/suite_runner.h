// The suite runner, internal to the harness: it takes a plan (suite_plan.h: made before it, plain data) and
// holds what running it changes (the searches, what runs, what is recorded), a source of units for the one
// runner (harness/jobs/unit_source.h), whose stages live in their own files:
//   suite.cpp               run_suites, and what is ready to run next (a job once its references have ended)
//   suite_progress.cpp      the plan described before it starts, each job's work for the remaining time
//   suite_shard.cpp         --shard K/N: the share this shard keeps, its plan recorded for merge
//   suite_jobs.cpp          a job started in the pool (harness/jobs/process_pool.h), its process, its record
//   step_search_driver.cpp  the step searches' probes, ready as their brackets ask
// Nothing outside the harness includes this (suite.h is the interface).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <csignal>
#include <deque>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "harness/jobs/process_pool.h"
#include "harness/jobs/progress.h"
#include "harness/jobs/run_job.h"
#include "harness/jobs/worker_process.h"
#include "harness/records/folder_lock.h"
#include "harness/suite/step_search.h"
#include "harness/suite/suite.h"
#include "harness/suite/suite_plan.h"

namespace ib::suite_internal {

using Clock = std::chrono::steady_clock;

// A job scored from another's run, with the references of its own law (loaded before the fork).
struct ScoredFrom {
  const PlannedJob* job;
  const ReferenceData* beam;
  const ReferenceData* chain;
};

// The suite's parts (run_suites): one plan, a source of units for the one runner (unit_source.h). What
// every part shares (the folder, the workers, the time limit, resume, shards) is the first part's; what
// decides a job's run (its scenario as cut, its measurement, its step search) is its own part's. A job is
// ready when the references it is compared with have ended (no phase waits for another), a step search's
// next probe when its previous one has ended.
class SuiteRunner : public SuiteSource {
 public:
  explicit SuiteRunner(SuitePlan plan) : plan_(std::move(plan)) {}
  SuiteRunner(const SuiteRunner&) = delete;
  SuiteRunner& operator=(const SuiteRunner&) = delete;

  // Checks and records the settings, records what cannot run (suite.cpp).
  void begin();
  std::optional<double> next_cost() override;
  std::string start_next(ProcessPool& pool) override;
  void ended(const ProcessEnd& end) override;
  SuiteOutcome finish() override;

 private:
  // A step search's group (step_search_driver.cpp): its bisection starts when its reference has ended.
  struct SearchGroup {
    const PlannedJob* job;  // the group's job with dt = 0: its id is the group's id
    StepGroup info;
    const StepSearchSettings* settings = nullptr;
    std::unique_ptr<StepSearch> search;  // made when its reference has ended
    bool with_chain = false, running = false, finished = false;
    int probe_index = -1;
    std::optional<PlannedJob> next_probe;  // its next probe, once chosen and not yet started
  };
  // The step searches as they go (step_search_driver.cpp).
  struct StepSearches {
    std::vector<SearchGroup> groups;
    std::deque<PlannedJob> probe_jobs;                  // their probes (a deque keeps their addresses)
    std::map<std::string, std::size_t> group_of_probe;  // a probe's job id -> its group
    SearchGroup* next = nullptr;                        // the group whose probe start_next starts
    std::map<std::string, std::string> recorded_lines;  // references and probes, for the searches
    std::set<std::string> planned_ids;                  // the plan's job ids (a probe may be one)
    std::set<std::string> awaited;                      // planned jobs a walk waits for as its next probe
    std::set<std::string> rows_done;                    // --resume: the searches recorded before
    int finished = 0, finished_probes = 0;              // how many probes a search takes, measured here
  };
  void begin_step_searches();
  // The group whose next probe is ready (choosing it, or ending the group's search when it needs none).
  SearchGroup* ready_search();
  void probe_ended(const PlannedJob& probe, const std::string& json);

  std::string folder_of(const PlannedJob& job) const { return settings_.out + "/runs/" + job.id; }

  // The shard's plan (shard_of), for `impactbench merge` to tell a finished shard from one that stopped early.
  void record_plan() const;

  // Refuses (std::invalid_argument) a --resume whose settings equal none of the folder's suites, naming
  // the keys that differ, unless --extend; with --extend, a shared job recorded under other settings.
  // Then records this suite's line unless it is there. A part after the first extends the folder, and
  // refuses a job it shares with an earlier part under other result-deciding settings.
  void check_and_record_settings(std::size_t part);

  // Before a step search starts (its references run first), its probes to come: about a bisection of
  // the whole grid, each costing what a probe at the grid's steps costs on average. The search itself
  // replaces this as it goes (run_step_searches).
  void expect_whole_searches();

  // What the suite runs, in one line each, before it starts.
  void describe_plan(int to_run) const;

  // The reference a job is compared with, read from its folder once and kept; null if it did not finish.
  const ReferenceData* reference(const std::string& id, const PlannedJob& job);  // read as job's part measures

  // Starts a job's process; "" when none was needed (its reference came from the cache).
  std::string start(const PlannedJob& job, ProcessPool& pool);
  // Whether a job's references have ended (recorded, or failed), and those of the jobs scored from its run:
  // it can run now.
  bool references_ended(const PlannedJob& job) const {
    const auto own_ended = [this](const PlannedJob& j) {
      return !unfinished_.count(j.beam_reference) && !unfinished_.count(j.chain_reference);
    };
    if (!own_ended(job)) return false;
    for (const PlannedJob* other : unrecorded_scored_from(job))
      if (!own_ended(*other)) return false;
    return true;
  }
  // The pending jobs whose references have ended (next_cost chooses among them).
  std::vector<const PlannedJob*> ready_jobs();
  // A reference job whose run the reference cache may hold or keep (SuiteSettings::reference_cache).
  bool cacheable(const PlannedJob& job) const {
    return job.kind != JobKind::engine && !settings_.reference_cache.empty() && unrecorded_scored_from(job).empty();
  }
  // Its entry's key in the reference cache (reference_cache.h): the same when looked up and when stored.
  nlohmann::ordered_json cache_key_of(const PlannedJob& job) const;

  // A job compared with a reference that a signal from outside stopped: it waits for --resume too (run
  // now, it would be recorded without its comparison).
  bool reference_stopped(const PlannedJob& job) const {
    return stopped_.count(job.beam_reference) > 0 || stopped_.count(job.chain_reference) > 0;
  }

  // What a job's folder keeps of its series: a reference always its window (engine runs are compared
  // with it, also on --resume), a step-search probe none unless asked (its summary and events say
  // whether the step is stable and accurate), any other run what --series says.
  Measurement measurement_of(const PlannedJob& job) const;

  // The job's process: its output goes to log.txt; its record to row.csv and row.jsonl for the parent.
  [[noreturn]] void run_in_child(const PlannedJob& job, const std::string& folder, const Scenario& scenario,
                                 const ReferenceData* beam, const ReferenceData* chain,
                                 const std::vector<ScoredFrom>& scored, int message_pipe);

  // Records a job that ended; returns its runs.jsonl line ("" when an interruption or a signal from
  // outside stopped it: nothing is recorded and --resume reruns it).
  std::string collect(const PlannedJob& job, const ProcessEnd& end);

  // The jobs scored from this job's run that are not recorded yet.
  std::vector<const PlannedJob*> unrecorded_scored_from(const PlannedJob& job) const;

  // Collects the record a job's process left in its folder into runs.jsonl and runs.csv (recorder.h), shows it
  // and returns its runs.jsonl line. The work done, for the cost per step: the steps an engine run took (a job scored
  // from another's run did none of its own, and its time is that run's).
  std::string append_row_of(const PlannedJob& job);

  void finish(const RunRecord& record);

  void count_and_show(const std::string& id, Verdict verdict, double units_done = -1, double compute_s = -1);

  const SuitePlan plan_;  // what runs: made before the runner (plan_suite; a shard's share: shard_of)
  const SuiteSettings& settings_ = plan_.shared();  // what the parts share
  std::set<std::string> recorded_;
  std::set<std::string>
      stopped_;  // jobs stopped from outside: neither they nor the jobs compared with them are recorded
  std::multimap<std::string, const PlannedJob*> scored_from_;  // a run's job id -> the jobs scored from its run
  std::map<std::string, std::unique_ptr<ReferenceData>> references_;
  std::vector<const PlannedJob*> pending_;            // jobs to run, not started
  std::set<std::string> unfinished_;                  // jobs pending or running: those compared with them wait
  std::map<std::string, const PlannedJob*> running_;  // by unit id
  const PlannedJob* next_ = nullptr;                  // what next_cost chose and start_next starts
  StepSearches searches_;
  std::unique_ptr<Progress> progress_;
  std::unique_ptr<FolderLock> lock_;  // the output folder's, held while the suite writes into it
  SuiteOutcome outcome_;
};

}  // namespace ib::suite_internal
