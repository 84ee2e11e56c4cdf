// A suite's job in the one pool of processes (suite_runner.h): started with the references it is compared
// with, run in its own process (a crash, an abort or a hang inside an engine's library costs that job alone),
// and its record collected from its folder when its process ends.
#include "harness/suite/suite_runner.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include "harness/jobs/progress.h"
#include "harness/jobs/recorder.h"
#include "harness/jobs/reference_cache.h"
#include "harness/records/number_text.h"
#include "harness/records/recorded_run.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

// The reference a job is compared with, read from its folder once and kept; null if it did not finish.
const ReferenceData* SuiteRunner::reference(const std::string& id, const PlannedJob& job) {
  if (id.empty()) return nullptr;
  auto found = references_.find(id);
  if (found == references_.end()) {
    std::unique_ptr<ReferenceData> data;
    try {
      data = std::make_unique<ReferenceData>(
          load_reference(settings_.out + "/runs/" + id, plan_.scenarios[job.scenario], plan_.part_of(job).measurement));
    } catch (const std::exception&) {
      data = nullptr;  // the reference failed: the job is recorded without errors against it
    }
    found = references_.emplace(id, std::move(data)).first;
  }
  return found->second.get();
}

std::string SuiteRunner::start(const PlannedJob& job, ProcessPool& pool) {
  const std::string folder = folder_of(job);
  clear_run_folder(folder);  // a previous, unfinished attempt's files; the runs below its id are others'
  const Scenario& scenario = plan_.scenarios[job.scenario];
  if (cacheable(job) && restore_cached_reference(settings_.reference_cache, cache_key_of(job), folder)) {
    progress_->estimate().start(job.id, progress_->now_s());
    const std::string json = append_row_of(job);  // as if its process had just ended
    if (!plan_.step_groups.empty()) searches_.recorded_lines[job.id] = json;
    ++outcome_.references_from_cache;
    return "";
  }
  // Load the references in this process, so that the job's process inherits them.
  const ReferenceData* beam = reference(job.beam_reference, job);
  const ReferenceData* chain = reference(job.chain_reference, job);
  std::vector<ScoredFrom> scored;
  for (const PlannedJob* other : unrecorded_scored_from(job)) {
    const std::string other_folder = folder_of(*other);
    clear_run_folder(other_folder);
    scored.push_back({other, reference(other->beam_reference, *other), reference(other->chain_reference, *other)});
  }
  const std::string unit = "suite " + settings_.out + " " + job.id;
  pool.start({unit, settings_.time_limit_s, folder + "/log.txt", /*append_log=*/false},
             [&](int message_pipe) { run_in_child(job, folder, scenario, beam, chain, scored, message_pipe); });
  progress_->estimate().start(job.id, progress_->now_s());
  return unit;
}

// What a job's folder keeps of its series: a reference its window at the output rate when a run is compared
// with it (also on --resume: the runs are scored against its series), else what --series says, and an
// ensemble's further start none (its metrics are what counts: the chains of a convergence study, say);
// a step-search probe none unless asked (its summary and events say whether the step is stable and accurate);
// any other run what --series says.
nlohmann::ordered_json SuiteRunner::cache_key_of(const PlannedJob& job) const {
  return reference_cache_key(plan_.scenarios[job.scenario], job.spec, measurement_of(job));
}

Measurement SuiteRunner::measurement_of(const PlannedJob& job) const {
  Measurement m = plan_.part_of(job).measurement;
  if (job.kind != JobKind::engine) {
    if (plan_.compared_references.count(job.id)) {
      if (m.series == SeriesOutput::none) m.series = SeriesOutput::window;
    } else if (job.spec.start.index > 0) {
      m.series = SeriesOutput::none;
    }
    m.series_rate_hz = 0;  // every sample: the runs compared with it are scored against it
  }
  if (job.step_probe && !plan_.part_of(job).keep_probe_series) m.series = SeriesOutput::none;
  return m;
}

// Why a job cannot be compared with the references it was planned with ("" when it can).
static std::string missing_reference(const PlannedJob& job, const ReferenceData* beam, const ReferenceData* chain) {
  std::string missing;
  if (job.kind != JobKind::engine) return missing;
  if (!job.beam_reference.empty() && !beam)
    missing = "its reference " + job.beam_reference + " did not finish (see its row)";
  if (!job.chain_reference.empty() && !chain)
    missing += (missing.empty() ? "its reference " : "; its reference ") + job.chain_reference +
               " did not finish (see its row)";
  return missing;
}

// The job's process: its output goes to log.txt; its record to row.csv and row.jsonl for the parent.
[[noreturn]] void SuiteRunner::run_in_child(const PlannedJob& job, const std::string& folder, const Scenario& scenario,
                                            const ReferenceData* beam, const ReferenceData* chain,
                                            const std::vector<ScoredFrom>& scored, int message_pipe) {
  RunRecord record;
  ReferenceData run_data;  // the run's metrics and trajectory, for the jobs scored from it
  bool ran = false;
  try {
    JobSpec spec = job.spec;
    spec.missing_reference = missing_reference(job, beam, chain);
    record = run_job(scenario, spec, measurement_of(job), beam, chain, folder, scored.empty() ? nullptr : &run_data,
                     settings_.simulators.make);
    ran = true;
  } catch (const OutputError& e) {
    send_and_exit(message_pipe, e.what());
  } catch (const std::exception& e) {
    record = unrunnable(job.id, scenario.name, scenario.source_path, job.spec.engine, to_string(job.spec.settings.law),
                        e.what());
    record.time_step_s = job.spec.settings.time_step_s;
    record.options = options_text(job.spec.settings.options);
    record.warnings = job.spec.warnings;
    record.start = job.spec.start;
  }
  record.job_id = job.id;
  record.chain_links = job.chain_links;
  try {
    write_text_file(folder + "/row.csv", csv_row(record));
    write_text_file(folder + "/row.jsonl", json_line(record));
    for (const ScoredFrom& other : scored) {
      const PlannedJob& o = *other.job;
      RunRecord r = record;
      if (ran) {
        r = score_for_law(scenario, record, run_data, o.id, o.spec.settings.law, measurement_of(o), other.beam,
                          other.chain, folder, folder_of(o), missing_reference(o, other.beam, other.chain));
      } else {  // the run failed: so does every job scored from it, for the same reason
        r.job_id = o.id;
        r.law = to_string(o.spec.settings.law);
        r.same_run_as = job.id;
      }
      r.chain_links = o.chain_links;
      write_text_file(folder_of(o) + "/row.csv", csv_row(r));
      write_text_file(folder_of(o) + "/row.jsonl", json_line(r));
    }
  } catch (const std::exception& e) {
    send_and_exit(message_pipe, e.what());
  }
  std::fflush(nullptr);
  _exit(0);
}

// Records a job that ended; returns its runs.jsonl line ("" when an interruption or a signal from
// outside stopped it: nothing is recorded and --resume reruns it).
std::string SuiteRunner::collect(const PlannedJob& job, const ProcessEnd& end) {
  const std::string folder = folder_of(job);
  const int status = end.status;
  const bool timed_out = end.timed_out;
  const std::string& output_error = end.output_error;
  if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerOutputError)
    throw OutputError(output_error.empty() ? output_error_text(folder, "write the run's files", 0) : output_error);
  const bool clean = !timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(folder + "/row.jsonl");
  if (clean) {
    if (cacheable(job) && read_recorded_run(read_text_file(folder + "/row.jsonl")).verdict == Verdict::ok)
      store_cached_reference(settings_.reference_cache, cache_key_of(job), folder);
    const std::vector<const PlannedJob*> scored = unrecorded_scored_from(job);
    std::string json;
    if (!recorded_.count(job.id)) {
      json = append_row_of(job);
    } else {  // recorded before: run again only for the jobs scored from it
      json = read_text_file(folder + "/row.jsonl");
      remove_row_files(folder);
    }
    for (const PlannedJob* other : scored) append_row_of(*other);
    return json;
  }
  if (interrupted()) return "";  // stopped by the interruption, not by its own fault: --resume reruns it
  if (stopped_from_outside(status, timed_out)) {  // the same, when the worker got the signal first
    ++outcome_.jobs_stopped;
    outcome_.stopped_by = WTERMSIG(status);
    stopped_.insert(job.id);
    std::fprintf(stderr, "suite: %s stopped by signal %d (%s) from outside, not recorded: --resume runs it again\n",
                 job.id.c_str(), WTERMSIG(status), strsignal(WTERMSIG(status)));
    return "";
  }
  const Scenario& s = plan_.scenarios[job.scenario];
  RunRecord record =
      unrunnable(job.id, s.name, s.source_path, job.spec.engine, to_string(job.spec.settings.law),
                 describe_exit(status, settings_.time_limit_s, timed_out, last_line(folder + "/log.txt")));
  record.time_step_s = job.spec.settings.time_step_s;
  record.options = options_text(job.spec.settings.options);
  record.warnings = job.spec.warnings;
  record.chain_links = job.chain_links;
  record.duration_s = s.duration_s;
  record.timed_out = timed_out;
  const std::vector<const PlannedJob*> scored = unrecorded_scored_from(job);
  if (!recorded_.count(job.id)) finish(record);
  for (const PlannedJob* other : scored) {  // scored from a run that did not end: failed alike
    RunRecord r = record;
    r.job_id = other->id;
    r.law = to_string(other->spec.settings.law);
    r.same_run_as = job.id;
    r.chain_links = other->chain_links;
    finish(r);
  }
  return json_line(record);
}

// The jobs scored from this job's run that are not recorded yet.
std::vector<const PlannedJob*> SuiteRunner::unrecorded_scored_from(const PlannedJob& job) const {
  std::vector<const PlannedJob*> jobs;
  const auto [first, last] = scored_from_.equal_range(job.id);
  for (auto it = first; it != last; ++it)
    if (!recorded_.count(it->second->id)) jobs.push_back(it->second);
  return jobs;
}

// Appends the record a job's process left in its folder (row.csv, row.jsonl), shows it and returns its
// runs.jsonl line. The work done, for the cost per step: the steps an engine run took (a job scored
// from another's run did none of its own, and its time is that run's).
std::string SuiteRunner::append_row_of(const PlannedJob& job) {
  const std::string folder = folder_of(job);
  const std::string json = collect_row(ResultTable{settings_.out, "runs"}, csv_header(RunRecord{}), folder);
  recorded_.insert(job.id);
  // what the progress estimate reads back: the steps taken (fewer than planned when it stopped
  // unstable) and the simulator's own time
  const RecordedRun recorded = read_recorded_run(json);
  const bool own_run = job.same_run_as.empty();
  const double steps = own_run && job.spec.settings.time_step_s > 0 && recorded.steps > 0 ? recorded.steps : -1;
  const double wall_time_s = std::isnan(recorded.wall_time_s) ? -1 : recorded.wall_time_s;
  count_and_show(job.id, recorded.verdict, own_run ? steps : 0, own_run ? wall_time_s : -1);
  return json;
}

void SuiteRunner::finish(const RunRecord& record) {
  append_run(settings_.out, record);
  recorded_.insert(record.job_id);
  count_and_show(record.job_id, record.verdict);
}

void SuiteRunner::count_and_show(const std::string& id, Verdict verdict, double units_done, double compute_s) {
  ++outcome_.jobs_run;
  if (verdict == Verdict::unstable || verdict == Verdict::failed) ++outcome_.not_ok;
  progress_->estimate().finish(id, progress_->now_s(), units_done, compute_s);
  progress_->job_done(id, verdict, std::max(1, settings_.jobs));
}

}  // namespace ib::suite_internal
