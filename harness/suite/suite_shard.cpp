// A suite's shards (suite_runner.h, --shard K/N): the planned order every shard agrees on, the share this shard
// keeps, and the record of its plan that `impactbench merge` checks.
#include <algorithm>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/jobs/shard_plan.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/suite/suite_runner.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

// A shard's folder holds that shard alone: another shard's plan (or a whole suite) in the same folder
// would leave it holding neither.
void SuiteRunner::check_same_shard() const {
  const std::vector<ShardPlan> plans = read_shard_plans(settings_.out);
  if (!settings_.shard) {
    if (!plans.empty())
      throw std::invalid_argument(settings_.out + " holds shard " + to_string(plans.front().shard) +
                                  " of a suite (shard.jsonl): resume it with --shard " +
                                  to_string(plans.front().shard));
    return;
  }
  if (plans.empty()) {
    if (!recorded_run_lines(settings_.out).empty())
      throw std::invalid_argument(settings_.out +
                                  " holds a whole suite's results, not a shard's: resume it without --shard " +
                                  to_string(*settings_.shard) + ", or choose another --out for the shard");
    return;
  }
  for (const ShardPlan& p : plans)
    if (p.shard != *settings_.shard)
      throw std::invalid_argument(settings_.out + " holds shard " + to_string(p.shard) +
                                  " of a suite (shard.jsonl), not --shard " + to_string(*settings_.shard) +
                                  ": resume it with --shard " + to_string(p.shard) +
                                  ", or choose another --out for this shard");
}

// What the suite records, in planned order: its job ids, and the keys of its step searches' rows.
std::vector<std::string> SuiteRunner::planned_job_ids() const {
  std::vector<std::string> ids;
  for (const RunRecord& r : plan_.unrunnable) ids.push_back(r.job_id);
  for (const PlannedJob& job : plan_.jobs) ids.push_back(job.id);
  return ids;
}

std::vector<std::string> SuiteRunner::planned_step_keys() const {
  std::vector<std::string> keys;
  for (const PlannedJob& group : plan_.step_groups)
    keys.push_back(step_row_key(step_group(plan_, group), *plan_.part_of(group).step_search));
  return keys;
}

// --shard K/N: keeps every N-th unit of work in planned order (the unrunnable jobs, then the engine
// jobs or step-search groups; the references when there is nothing else) and the references those
// units are compared with.
void SuiteRunner::keep_only_this_shard() {
  const Shard& shard = *settings_.shard;
  const bool references_alone =
      plan_.step_groups.empty() &&
      std::none_of(plan_.jobs.begin(), plan_.jobs.end(), [](const PlannedJob& j) { return j.kind == JobKind::engine; });
  std::size_t unit = 0;
  std::vector<RunRecord> unrunnable;
  for (RunRecord& r : plan_.unrunnable)
    if (in_shard(unit++, shard)) unrunnable.push_back(std::move(r));
  plan_.unrunnable = std::move(unrunnable);
  std::vector<PlannedJob> groups;
  std::set<std::string> references;  // those the kept units are compared with
  const auto keep_references_of = [&](const PlannedJob& job) {
    for (const std::string& id : {job.beam_reference, job.chain_reference})
      if (!id.empty()) references.insert(id);
  };
  for (const PlannedJob& group : plan_.step_groups)
    if (in_shard(unit++, shard)) {
      groups.push_back(group);
      keep_references_of(group);
    }
  plan_.step_groups = std::move(groups);
  std::set<std::string> kept;
  for (const PlannedJob& job : plan_.jobs)
    if ((job.kind == JobKind::engine || references_alone) && job.same_run_as.empty() && in_shard(unit++, shard)) {
      kept.insert(job.id);
      keep_references_of(job);
    }
  for (const PlannedJob& job : plan_.jobs)  // a job scored from another's run goes with that run
    if (!job.same_run_as.empty() && kept.count(job.same_run_as)) {
      kept.insert(job.id);
      keep_references_of(job);
    }
  for (const PlannedJob& job : plan_.jobs)  // a chain reference is compared with its beam reference
    if (references.count(job.id) && !job.beam_reference.empty()) references.insert(job.beam_reference);
  std::vector<PlannedJob> jobs;
  for (const PlannedJob& job : plan_.jobs)
    if (kept.count(job.id) || references.count(job.id)) jobs.push_back(job);
  plan_.jobs = std::move(jobs);
}

// The shard's plan, for `impactbench merge` to tell a finished shard from one that stopped early.
// suite: the digest of the whole suite's plan.
void SuiteRunner::record_plan(const std::string& suite) const {
  record_shard_plan(settings_.out, ShardPlan{*settings_.shard, suite, planned_job_ids(), planned_step_keys(),
                                             settings_.resume_command});
  // A shard is a suite's folder even when it gets no job (more shards than units): the report reads it.
  if (!fs::exists(settings_.out + "/runs.jsonl")) {
    write_text_file(settings_.out + "/runs.jsonl", "");
    write_text_file(settings_.out + "/runs.csv", csv_header(RunRecord{}));
  }
}

}  // namespace ib::suite_internal
