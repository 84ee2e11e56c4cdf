// What each part of a study's suites and searches runs (suite.h, count_part_runs): `study --plan`'s counts and the
// work its cost estimate reads, from the plan the suites would run.
#include <set>

#include "harness/suite/suite_plan.h"

namespace ib {

std::vector<PartRuns> count_part_runs(const std::vector<SuiteSettings>& parts) {
  using namespace suite_internal;
  const SuitePlan plan = plan_suite(parts, true);  // the study's run says its warnings
  std::map<std::string, const PlannedJob*> job_of;
  for (const PlannedJob& job : plan.jobs) job_of[job.id] = &job;
  std::vector<PartRuns> counted(plan.parts.size());
  std::set<std::string> seen;  // jobs counted by an earlier part (or earlier in this one: a shared chain reference)
  for (std::size_t part = 0; part < plan.parts.size(); ++part) {
    std::set<std::string> mine;
    for (const std::string& id : plan.part_jobs[part]) {
      if (!mine.insert(id).second) continue;  // a chain reference several engines of the part compare with
      if (!seen.insert(id).second) {
        ++counted[part].shared;
        continue;
      }
      ++counted[part].runs;
      const auto job = job_of.find(id);
      if (job == job_of.end()) continue;  // unrunnable: recorded as failed, nothing runs
      if (!job->second->same_run_as.empty()) {
        ++counted[part].scored_only;
        continue;
      }
      const JobSpec& spec = job->second->spec;
      counted[part].to_run.push_back({spec.engine, spec.settings.options, spec.settings.time_step_s,
                                      plan.scenarios[job->second->scenario].duration_s});
    }
  }
  for (const PlannedJob& group : plan.step_groups) ++counted[plan.scenario_part[group.scenario]].step_searches;
  return counted;
}

}  // namespace ib
