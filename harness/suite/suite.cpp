#include "harness/suite/suite.h"
#include "harness/suite/suite_runner.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "harness/jobs/campaign_folder.h"
#include "harness/records/engines_file.h"
#include "harness/records/recorded_run.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

// A job that cannot run at all (a malformed scenario, a law the scenario has no parameters for): it
// is recorded as failed with the reason, and the suite goes on.
RunRecord unrunnable(const std::string& id, const std::string& scenario, const std::string& file,
                     const std::string& engine, const std::string& law, const std::string& reason) {
  RunRecord r;
  r.job_id = id;
  r.scenario = scenario;
  r.scenario_file = file;
  r.engine = engine;
  r.law = law;
  r.verdict = Verdict::failed;
  r.reason = reason;
  return r;
}

// The step search judges "within tolerance" with the verdicts' own tolerances: one record.
SuiteSettings with_one_tolerance_record(SuiteSettings settings) {
  if (settings.step_search) settings.step_search->tolerance = settings.measurement.verdicts.accuracy;
  return settings;
}

std::vector<SuiteSettings> with_one_tolerance_record(const std::vector<SuiteSettings>& parts) {
  if (parts.empty()) throw std::logic_error("a suite with no part");
  std::vector<SuiteSettings> checked;
  for (const SuiteSettings& part : parts) checked.push_back(with_one_tolerance_record(part));
  return checked;
}

void SuiteRunner::begin() {
  lock_ = open_campaign_folder(settings_.out, CampaignKind::suite);
  check_same_shard(settings_.out, CampaignKind::suite, settings_.shard, !recorded_run_lines(settings_.out).empty());
  if (settings_.resume || settings_.extend) {
    std::vector<std::string> repairs;
    recorded_ = repair_and_list_runs(settings_.out, &repairs);
    for (const std::string& repair : repairs) std::fprintf(stderr, "suite: repaired %s\n", repair.c_str());
  }
  refuse_results_without_resume(settings_.out, CampaignKind::suite, settings_.resume || settings_.extend);
  for (std::size_t part = 0; part < plan_.parts.size(); ++part) check_and_record_settings(part);
  if (settings_.shard) record_plan();
  for (const PlannedJob& job : plan_.jobs)
    if (!job.same_run_as.empty()) scored_from_.emplace(job.same_run_as, &job);
  int unrecorded_unrunnable = 0;
  for (const RunRecord& r : plan_.unrunnable) unrecorded_unrunnable += recorded_.count(r.job_id) ? 0 : 1;
  int to_run = unrecorded_unrunnable;
  for (const auto& job : plan_.jobs) to_run += recorded_.count(job.id) ? 0 : 1;
  outcome_.jobs_skipped = static_cast<int>(plan_.jobs.size() + plan_.unrunnable.size()) - to_run;
  progress_ = std::make_unique<Progress>(to_run);
  for (const auto& job : plan_.jobs)
    if (!recorded_.count(job.id)) progress_->estimate().plan(job.id, work_of(plan_, job));
  if (!plan_.step_groups.empty()) expect_whole_searches();
  describe_plan(to_run);
  outcome_.jobs_total = static_cast<int>(plan_.jobs.size() + plan_.unrunnable.size());
  for (const RunRecord& r : plan_.unrunnable)
    if (!recorded_.count(r.job_id)) finish(r);  // recorded once: a --resume does not add it again
  for (const PlannedJob& job : plan_.jobs) {
    if (job.same_run_as.empty() && (!recorded_.count(job.id) || !unrecorded_scored_from(job).empty())) {
      pending_.push_back(&job);
      unfinished_.insert(job.id);
    }
  }
  begin_step_searches();
}

// The jobs whose references have ended. A job compared with a reference that a signal from outside stopped
// waits for --resume (run now, it would be recorded without its comparison): it leaves the pending jobs.
std::vector<const PlannedJob*> SuiteRunner::ready_jobs() {
  std::vector<const PlannedJob*> ready;
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (reference_stopped(**it)) {
      ++outcome_.jobs_stopped;
      unfinished_.erase((*it)->id);
      it = pending_.erase(it);
      continue;
    }
    if (references_ended(**it)) ready.push_back(*it);
    ++it;
  }
  return ready;
}

// What waits for a unit decides its turn before its own cost does (the critical path first, so that no chain
// of units is left to run alone at the end): a reference first, cheap, since the jobs compared with it wait for
// it; then a step search's probe, since each probe waits for the one before it (a search is a chain whose
// length only its probes reveal), and a job a walk waits for as its next probe, for the same reason; then, of
// the other jobs, a kind not measured yet, then the costliest (choose_next, the cost model sweeps share).
std::optional<double> SuiteRunner::next_cost() {
  const std::vector<const PlannedJob*> ready = ready_jobs();
  const auto reference =
      std::find_if(ready.begin(), ready.end(), [](const PlannedJob* job) { return job->kind != JobKind::engine; });
  next_ = reference != ready.end() ? *reference : nullptr;
  searches_.next = next_ ? nullptr : ready_search();
  if (next_ || searches_.next) return kUnknownCost;
  const auto awaited = std::find_if(ready.begin(), ready.end(),
                                    [this](const PlannedJob* job) { return searches_.awaited.count(job->id) > 0; });
  if (awaited != ready.end()) {
    next_ = *awaited;
    return kUnknownCost;
  }
  if (ready.empty()) return std::nullopt;
  std::vector<JobWork> work;
  for (const PlannedJob* job : ready) work.push_back(work_of(plan_, *job));
  const NextUnit chosen = choose_next(progress_->estimate(), work);
  next_ = ready[chosen.index];
  return chosen.cost_s;
}

std::string SuiteRunner::start_next(ProcessPool& pool) {
  const PlannedJob* job = next_;
  if (next_) {
    pending_.erase(std::find(pending_.begin(), pending_.end(), next_));
  } else {  // a step search's probe
    SearchGroup& g = *searches_.next;
    searches_.probe_jobs.push_back(*g.next_probe);
    g.next_probe.reset();
    g.running = true;
    job = &searches_.probe_jobs.back();
    searches_.group_of_probe[job->id] = static_cast<std::size_t>(&g - searches_.groups.data());
    unfinished_.insert(job->id);
    progress_->add_to_total(1);
    progress_->estimate().plan(job->id, work_of(plan_, *job));
  }
  next_ = nullptr;
  searches_.next = nullptr;
  const std::string unit = start(*job, pool);
  if (unit.empty()) {  // recorded from the reference cache
    unfinished_.erase(job->id);
    return unit;
  }
  running_[unit] = job;
  return unit;
}

void SuiteRunner::ended(const ProcessEnd& end) {
  const PlannedJob& job = *running_.at(end.unit);
  running_.erase(end.unit);
  const std::string json = collect(job, end);
  unfinished_.erase(job.id);
  if (!json.empty() && !plan_.step_groups.empty())
    searches_.recorded_lines[job.id] = json;  // a search's reference or probe
  if (job.step_probe) probe_ended(job, json);
}

SuiteOutcome SuiteRunner::finish() {
  if (interrupted()) outcome_.interrupted_by = interrupt_signal;
  for (const auto& [id, line] : recorded_run_lines(settings_.out)) {
    const Verdict verdict = read_recorded_run(line).verdict;
    ++outcome_.recorded;
    outcome_.not_ok_recorded += verdict == Verdict::unstable || verdict == Verdict::failed ? 1 : 0;
  }
  return outcome_;
}

}  // namespace ib::suite_internal

namespace ib {

CampaignEnd end_of(const SuiteOutcome& outcome) {
  return {outcome.interrupted_by, outcome.jobs_stopped, outcome.stopped_by, outcome.not_ok_recorded};
}

SuiteOutcome run_suite(const SuiteSettings& settings) { return run_suites({settings}); }

std::unique_ptr<SuiteSource> prepare_suites(const std::vector<SuiteSettings>& parts) {
  auto runner = std::make_unique<suite_internal::SuiteRunner>(suite_internal::plan_to_run(parts));
  runner->begin();
  return runner;
}

SuiteOutcome run_suites(const std::vector<SuiteSettings>& parts) {
  const InterruptionHandler handler;  // outlives the pool, which stops its workers when it ends
  const std::unique_ptr<SuiteSource> suites = prepare_suites(parts);
  run_units({suites.get()}, parts.front().jobs);
  return with_engines_file(parts.front().out, parts.front().simulators, suites->finish());
}

}  // namespace ib
