// A suite's shards (suite_runner.h, --shard K/N): the planned order every shard agrees on, the share this shard
// keeps, and the record of its plan that `impactbench merge` checks.
#include <algorithm>
#include <filesystem>
#include <optional>
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

std::vector<std::string> planned_job_ids(const SuitePlan& plan) {
  std::vector<std::string> ids;
  for (const RunRecord& r : plan.unrunnable) ids.push_back(r.job_id);
  for (const PlannedJob& job : plan.jobs) ids.push_back(job.id);
  return ids;
}

std::vector<std::string> planned_step_keys(const SuitePlan& plan) {
  std::vector<std::string> keys;
  for (const PlannedJob& group : plan.step_groups)
    keys.push_back(step_row_key(step_group(plan, group), *plan.part_of(group).step_search));
  return keys;
}

namespace {

// Every shard of one suite agrees on it: the whole plan and the parts' settings (without the scenario files'
// paths, which the shards' machines may name differently).
std::string whole_suite_digest(const SuitePlan& plan) {
  std::vector<std::string> whole = planned_job_ids(plan);
  for (std::string& key : planned_step_keys(plan)) whole.push_back(std::move(key));
  for (std::size_t part = 0; part < plan.parts.size(); ++part) {
    nlohmann::ordered_json settings = settings_record(plan, part);
    settings.erase("scenario_files");
    whole.push_back(settings.dump());
  }
  return plan_digest(whole);
}

}  // namespace

SuitePlan shard_of(SuitePlan plan, const Shard& shard) {
  plan.whole_suite_digest = whole_suite_digest(plan);
  const bool references_alone =
      plan.step_groups.empty() &&
      std::none_of(plan.jobs.begin(), plan.jobs.end(), [](const PlannedJob& j) { return j.kind == JobKind::engine; });
  std::size_t unit = 0;
  std::vector<RunRecord> unrunnable;
  for (RunRecord& r : plan.unrunnable)
    if (in_shard(unit++, shard)) unrunnable.push_back(std::move(r));
  plan.unrunnable = std::move(unrunnable);
  std::vector<PlannedJob> groups;
  std::set<std::string> references;  // those the kept units are compared with
  const auto keep_references_of = [&](const PlannedJob& job) {
    for (const std::string& id : {job.beam_reference, job.chain_reference})
      if (!id.empty()) references.insert(id);
  };
  for (const PlannedJob& group : plan.step_groups)
    if (in_shard(unit++, shard)) {
      groups.push_back(group);
      keep_references_of(group);
    }
  plan.step_groups = std::move(groups);
  std::set<std::string> kept;
  for (const PlannedJob& job : plan.jobs)
    if ((job.kind == JobKind::engine || references_alone) && job.same_run_as.empty() && in_shard(unit++, shard)) {
      kept.insert(job.id);
      keep_references_of(job);
    }
  for (const PlannedJob& job : plan.jobs)  // a job scored from another's run goes with that run
    if (!job.same_run_as.empty() && kept.count(job.same_run_as)) {
      kept.insert(job.id);
      keep_references_of(job);
    }
  for (const PlannedJob& job : plan.jobs)  // a chain reference is compared with its beam reference
    if (references.count(job.id) && !job.beam_reference.empty()) references.insert(job.beam_reference);
  std::vector<PlannedJob> jobs;
  for (const PlannedJob& job : plan.jobs)
    if (kept.count(job.id) || references.count(job.id)) jobs.push_back(job);
  plan.jobs = std::move(jobs);
  return plan;
}

// The shard's plan, for `impactbench merge` to tell a finished shard from one that stopped early.
SuitePlan plan_to_run(const std::vector<SuiteSettings>& parts) {
  SuitePlan plan = plan_suite(parts);
  const std::optional<Shard> shard = plan.shared().shard;
  return shard ? shard_of(std::move(plan), *shard) : plan;
}

// The shard's plan (shard_of), for `impactbench merge` to tell a finished shard from one that stopped early.
void SuiteRunner::record_plan() const {
  record_shard_plan(settings_.out, ShardPlan{*settings_.shard, plan_.whole_suite_digest, planned_job_ids(plan_),
                                             planned_step_keys(plan_), settings_.resume_command});
  // A shard is a suite's folder even when it gets no job (more shards than units): the report reads it.
  if (!fs::exists(settings_.out + "/runs.jsonl")) {
    write_text_file(settings_.out + "/runs.jsonl", "");
    write_text_file(settings_.out + "/runs.csv", csv_header(RunRecord{}));
  }
}

}  // namespace ib::suite_internal
