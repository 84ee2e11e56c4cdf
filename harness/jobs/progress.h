// A campaign's progress and its one cost model, shared by suites and sweeps (so that their units' costs compare
// on the one runner, unit_source.h): how many jobs are done and how long the rest will take. The remaining time is
// estimated from each job's work (its steps: simulated time over time step; for an adaptive simulator
// its simulated time) and the measured cost per unit of work of its kind (engine and options), not from
// the jobs done so far: a suite runs its cheap references first and its costly engine runs last, so a
// mean over the jobs done says too little at first.
#pragma once

#include <chrono>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/jobs/unit_source.h"
#include "harness/scoring/verdict.h"

namespace ib {

// What a job is for the estimate: its kind (runs of one kind cost the same per unit) and its work.
struct JobWork {
  std::string kind;  // e.g. "mujoco/contact=native"; the engine alone is the kind's fallback
  std::string engine;
  double units = 0;      // steps, or simulated seconds for an adaptive simulator
  bool in_steps = true;  // units are steps (false: simulated seconds)
  // Jobs that tend to run the same share of their steps (an engine, options and step: Bullet's hinge
  // springs diverge at 1e-4 s within the first second, whatever the case); "": the kind.
  std::string stop_key;
};

// A run's work: its steps at a fixed step dt_s > 0, else its simulated seconds (an adaptive simulator), of the
// kind engine/options; it stops early as runs of the same kind and step do (stop_key). A sweep's chain is the
// work of its rows added.
JobWork run_work(const std::string& engine, const std::string& options_text, double dt_s, double simulated_s);

// The estimate alone, without a clock or a screen, so that it can be tested on a synthetic job list.
class RemainingTime {
 public:
  void plan(const std::string& id, const JobWork& work);  // a job to run
  void start(const std::string& id, double now_s);        // it started at now_s
  // It ended at now_s after units_done of its work (< 0: all of it; fewer when it stopped early), of
  // which the simulator itself took compute_s (< 0: unknown); the rest is the job's overhead (its
  // process, references, files), the same for every job, so that a run that stopped early does not
  // make its kind's steps look costly.
  void finish(const std::string& id, double now_s, double units_done = -1, double compute_s = -1);
  // Jobs not planned yet but expected (a step search's later probes): count jobs like `work`, under a
  // key that a later call replaces.
  void expect(const std::string& key, const JobWork& work, int count);
  // Seconds until every planned job has ended on `workers` processes; negative when a job's cost
  // cannot be estimated yet (nothing of its unit measured).
  double remaining_s(double now_s, int workers) const;
  bool measured(const std::string& kind) const;      // a job of this kind has finished after running
  bool started_kind(const std::string& kind) const;  // a job of this kind is running or has run
  double cost_s(const JobWork& work) const;          // estimated seconds of a job; negative: unknown

 private:
  struct Job {
    JobWork work;
    double started_s = -1;
    bool finished = false;
  };
  // Measured seconds per unit of work: of the kind, else of the engine, else of every finished job
  // with the same unit; negative when none is measured.
  double cost_per_unit(const JobWork& work) const;
  std::map<std::string, Job> jobs_;
  std::set<std::string> started_kinds_;
  std::map<std::string, std::pair<JobWork, int>> expected_;
  struct Sum {
    double seconds = 0, units = 0;
  };
  std::map<std::string, Sum> by_kind_, by_engine_;
  Sum by_unit_[2];                        // [in_steps]
  Sum overhead_;                          // seconds of a job beyond its simulator's own, over jobs (units: jobs)
  std::map<std::string, Sum> share_run_;  // by stop key: steps run (seconds) over steps planned (units)
  // The units a job will likely run: its planned ones times the share its stop key's jobs ran.
  double likely_units(const JobWork& work) const;
};

// Which of the pending jobs to start next (an index into pending): first a job of each kind not yet
// measured, so that every kind's cost is known early, then the costliest, so that a pool of workers
// does not end waiting for one long job. The plan (and so the shards) stays as planned.
std::size_t next_to_start(const RemainingTime& estimate, const std::vector<JobWork>& pending);

// next_to_start's choice with its estimated cost [s] as the one runner compares units (UnitSource::next_cost):
// kUnknownCost when nothing of its kind, its engine or its unit is measured yet. pending must not be empty.
struct NextUnit {
  std::size_t index = 0;
  double cost_s = 0;
};
NextUnit choose_next(const RemainingTime& estimate, const std::vector<JobWork>& pending);

// Progress on stderr: a bar that redraws itself on a terminal, one plain line per job elsewhere.
class Progress {
 public:
  explicit Progress(int jobs_to_run);
  void add_to_total(int jobs) { total_ += jobs; }  // jobs planned on the fly (step-search probes)
  RemainingTime& estimate() { return estimate_; }
  double now_s() const;
  void job_done(const std::string& id, Verdict verdict, int workers);

 private:
  int total_, done_ = 0;
  std::chrono::steady_clock::time_point start_;
  bool terminal_;
  RemainingTime estimate_;
};

}  // namespace ib
