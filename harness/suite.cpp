#include "harness/suite.h"

#include <fcntl.h>
#include <sys/prctl.h>
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
#include <thread>

#include "harness/number_text.h"
#include "harness/progress.h"
#include "harness/recorded_run.h"
#include "harness/reporters.h"
#include "harness/run_files.h"
#include "model/scenario_toml.h"

namespace ib {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

enum class JobKind { beam_reference, chain_reference, engine };

struct PlannedJob {
  std::string id;
  JobKind kind = JobKind::engine;
  std::size_t scenario = 0;     // index into the loaded scenarios
  JobSpec spec;
  std::string beam_reference;   // job ids of the references this job is compared with ("" if none)
  std::string chain_reference;
  int chain_links = 0;
  bool step_probe = false;      // a probe of a step search (its series is kept only on request)
  // The job whose run this one scores against its own law's references (native contact ignores the
  // law): it is recorded by that job's process, never run itself. "" for a job that runs.
  std::string same_run_as;
};

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

std::string describe_exit(int status, double time_limit_s, bool timed_out, const std::string& log_tail) {
  std::ostringstream why;
  if (timed_out) why << kTimeLimitReason << " of " << time_limit_s << " s";
  else if (WIFSIGNALED(status)) why << "the job's process died of signal " << WTERMSIG(status) << " (" << strsignal(WTERMSIG(status)) << ")";
  else if (WIFEXITED(status)) why << "the job's process exited with code " << WEXITSTATUS(status) << " without a result";
  else why << "the job's process ended abnormally";
  if (!log_tail.empty()) why << "; its last output: " << log_tail;
  return why.str();
}

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last.size() > 300 ? last.substr(0, 300) + "..." : last;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// ---- Interruption: SIGINT and SIGTERM stop the suite between results, never in the middle of one.
// The handler only notes the signal; the runner stops its workers, records nothing half-done and
// returns. A terminal's Ctrl-C reaches the workers too (same process group): they die at once, and
// what they had not finished is not recorded, so that --resume runs it again.

volatile std::sig_atomic_t interrupt_signal = 0;

extern "C" void note_interruption(int signal) { interrupt_signal = signal; }

// Installs the handler for the runner's lifetime and restores the previous one after.
class InterruptionHandler {
 public:
  InterruptionHandler() {
    interrupt_signal = 0;
    struct sigaction action {};
    action.sa_handler = note_interruption;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &previous_int_);
    sigaction(SIGTERM, &action, &previous_term_);
  }
  ~InterruptionHandler() {
    sigaction(SIGINT, &previous_int_, nullptr);
    sigaction(SIGTERM, &previous_term_, nullptr);
  }
  InterruptionHandler(const InterruptionHandler&) = delete;
  InterruptionHandler& operator=(const InterruptionHandler&) = delete;

 private:
  struct sigaction previous_int_ {}, previous_term_ {};
};

bool interrupted() { return interrupt_signal != 0; }

// In a job's process, right after fork: the default signal actions (the parent's handler would only
// set a flag nobody reads), and death with the parent, so that a suite killed with SIGKILL leaves no
// orphan writing into the folder a --resume is about to use.
void become_worker(pid_t parent) {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(1);  // the parent died before prctl
}

// ---- Write errors inside a job's process: the message goes to the parent through a pipe and the
// process exits with this code; the parent stops the suite with that message (OutputError).
constexpr int kWorkerOutputError = 75;

void send_and_exit(int pipe_fd, const std::string& message) {
  if (pipe_fd >= 0) {
    const ssize_t written = write(pipe_fd, message.data(), std::min<std::size_t>(message.size(), 4000));
    (void)written;
  }
  _exit(kWorkerOutputError);
}

std::string receive(int pipe_fd) {
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fd, buffer, sizeof buffer)) > 0;) message.append(buffer, static_cast<std::size_t>(n));
  return message;
}

// A job scored from another's run, with the references of its own law (loaded before the fork).
struct ScoredFrom {
  const PlannedJob* job;
  const ReferenceData* beam;
  const ReferenceData* chain;
};

// The step search judges "within tolerance" with the verdicts' own tolerances: one record.
SuiteSettings with_one_tolerance_record(SuiteSettings settings) {
  if (settings.step_search) settings.step_search->tolerance = settings.measurement.verdicts.accuracy;
  return settings;
}

class SuiteRunner {
 public:
  explicit SuiteRunner(const SuiteSettings& settings) : settings_(with_one_tolerance_record(settings)) {}
  // On an exception (a result that cannot be written), no worker outlives the runner.
  ~SuiteRunner() { stop_workers(/*collect_finished=*/false); }
  SuiteRunner(const SuiteRunner&) = delete;
  SuiteRunner& operator=(const SuiteRunner&) = delete;

  SuiteOutcome run() {
    std::error_code error;
    fs::create_directories(settings_.out, error);
    if (error) throw OutputError(output_error_text(settings_.out, "create the output folder", error.value()));
    if (access(settings_.out.c_str(), W_OK) != 0)
      throw OutputError(output_error_text(settings_.out, "write into the output folder", errno));
    check_same_shard();
    if (settings_.resume) recorded_ = repair_and_list_runs(settings_.out);
    else if (fs::exists(settings_.out + "/runs.jsonl"))
      throw std::runtime_error(settings_.out + " already holds a suite's results (runs.jsonl): pass --resume to continue it, or choose another --out");
    plan();
    if (settings_.shard) {
      std::vector<std::string> whole = planned_job_ids();
      for (std::string& key : planned_step_keys()) whole.push_back(std::move(key));
      const std::string suite = plan_digest(whole);
      keep_only_this_shard();
      record_plan(suite);
    }
    for (const PlannedJob& job : jobs_)
      if (!job.same_run_as.empty()) scored_from_.emplace(job.same_run_as, &job);
    int to_run = static_cast<int>(unrunnable_.size());
    for (const auto& job : jobs_) to_run += recorded_.count(job.id) ? 0 : 1;
    outcome_.jobs_skipped = static_cast<int>(jobs_.size()) - (to_run - static_cast<int>(unrunnable_.size()));
    progress_ = std::make_unique<Progress>(to_run);
    for (const auto& job : jobs_)
      if (!recorded_.count(job.id)) progress_->estimate().plan(job.id, work_of(job));
    if (settings_.step_search) expect_whole_searches();
    describe_plan(to_run);
    outcome_.jobs_total = static_cast<int>(jobs_.size() + unrunnable_.size());
    for (const RunRecord& r : unrunnable_) finish(r);
    // References first (beam, then chain): engine jobs are compared with them.
    for (JobKind phase : {JobKind::beam_reference, JobKind::chain_reference, JobKind::engine}) {
      if (phase == JobKind::engine && settings_.step_search) {
        run_step_searches();
        continue;
      }
      std::vector<const PlannedJob*> pending;
      for (const PlannedJob& job : jobs_)
        if (job.kind == phase && job.same_run_as.empty() && (!recorded_.count(job.id) || !unrecorded_scored_from(job).empty()))
          pending.push_back(&job);
      while (!pending.empty()) {
        while (!interrupted() && static_cast<int>(running_.size()) >= std::max(1, settings_.jobs)) reap(true);
        if (interrupted()) break;
        std::vector<JobWork> work;
        for (const PlannedJob* job : pending) work.push_back(work_of(*job));
        const auto next = pending.begin() + next_to_start(progress_->estimate(), work);
        start(**next);
        pending.erase(next);
      }
      while (!interrupted() && !running_.empty()) reap(true);
      if (interrupted()) break;
    }
    if (interrupted()) {
      stop_workers(/*collect_finished=*/true);
      outcome_.interrupted_by = interrupt_signal;
    }
    return outcome_;
  }

 private:
  struct Running {
    const PlannedJob* job;
    Clock::time_point started;
    bool timed_out = false;
    int message_pipe = -1;  // read end: a write error's message from the job's process
  };

  // Stops every worker. With collect_finished, a job that ended cleanly before the stop is recorded
  // first (nothing finished is lost); the others are killed and not recorded (--resume reruns them).
  void stop_workers(bool collect_finished) {
    if (collect_finished) {
      for (int status = 0;;) {
        const pid_t pid = waitpid(-1, &status, WNOHANG);
        if (pid <= 0) break;
        auto it = running_.find(pid);
        if (it == running_.end()) continue;
        const Running r = it->second;
        running_.erase(it);
        collect(*r.job, status, r.timed_out, r.message_pipe);
      }
    }
    for (const auto& [pid, r] : running_) kill(pid, SIGKILL);
    for (const auto& [pid, r] : running_) {
      int status = 0;
      waitpid(pid, &status, 0);
      if (r.message_pipe >= 0) close(r.message_pipe);
    }
    running_.clear();
  }

  std::string folder_of(const PlannedJob& job) const { return settings_.out + "/runs/" + job.id; }

  // A shard's folder holds that shard alone: another shard's plan (or a whole suite) in the same folder
  // would leave it holding neither.
  void check_same_shard() const {
    const std::vector<ShardPlan> plans = read_shard_plans(settings_.out);
    if (!settings_.shard) {
      if (!plans.empty())
        throw std::invalid_argument(settings_.out + " holds shard " + to_string(plans.front().shard) +
                                    " of a suite (shard.jsonl): resume it with --shard " + to_string(plans.front().shard));
      return;
    }
    if (plans.empty()) {
      if (!recorded_run_lines(settings_.out).empty())
        throw std::invalid_argument(settings_.out + " holds a whole suite's results, not a shard's: resume it without --shard " +
                                    to_string(*settings_.shard) + ", or choose another --out for the shard");
      return;
    }
    for (const ShardPlan& p : plans)
      if (p.shard != *settings_.shard)
        throw std::invalid_argument(settings_.out + " holds shard " + to_string(p.shard) + " of a suite (shard.jsonl), not --shard " +
                                    to_string(*settings_.shard) + ": resume it with --shard " + to_string(p.shard) +
                                    ", or choose another --out for this shard");
  }

  // What the suite records, in planned order: its job ids, and the keys of its step searches' rows.
  std::vector<std::string> planned_job_ids() const {
    std::vector<std::string> ids;
    for (const RunRecord& r : unrunnable_) ids.push_back(r.job_id);
    for (const PlannedJob& job : jobs_) ids.push_back(job.id);
    return ids;
  }
  std::vector<std::string> planned_step_keys() const {
    std::vector<std::string> keys;
    for (const PlannedJob& group : step_groups_) keys.push_back(step_row_key(step_group(group), *settings_.step_search));
    return keys;
  }

  // --shard K/N: keeps every N-th unit of work in planned order (the unrunnable jobs, then the engine
  // jobs or step-search groups; the references when there is nothing else) and the references those
  // units are compared with.
  void keep_only_this_shard() {
    const Shard& shard = *settings_.shard;
    const bool references_alone = step_groups_.empty() && std::none_of(jobs_.begin(), jobs_.end(), [](const PlannedJob& j) {
                                    return j.kind == JobKind::engine;
                                  });
    std::size_t unit = 0;
    std::vector<RunRecord> unrunnable;
    for (RunRecord& r : unrunnable_)
      if (in_shard(unit++, shard)) unrunnable.push_back(std::move(r));
    unrunnable_ = std::move(unrunnable);
    std::vector<PlannedJob> groups;
    std::set<std::string> references;  // those the kept units are compared with
    const auto keep_references_of = [&](const PlannedJob& job) {
      for (const std::string& id : {job.beam_reference, job.chain_reference})
        if (!id.empty()) references.insert(id);
    };
    for (const PlannedJob& group : step_groups_)
      if (in_shard(unit++, shard)) {
        groups.push_back(group);
        keep_references_of(group);
      }
    step_groups_ = std::move(groups);
    std::set<std::string> kept;
    for (const PlannedJob& job : jobs_)
      if ((job.kind == JobKind::engine || references_alone) && job.same_run_as.empty() && in_shard(unit++, shard)) {
        kept.insert(job.id);
        keep_references_of(job);
      }
    for (const PlannedJob& job : jobs_)  // a job scored from another's run goes with that run
      if (!job.same_run_as.empty() && kept.count(job.same_run_as)) {
        kept.insert(job.id);
        keep_references_of(job);
      }
    for (const PlannedJob& job : jobs_)  // a chain reference is compared with its beam reference
      if (references.count(job.id) && !job.beam_reference.empty()) references.insert(job.beam_reference);
    std::vector<PlannedJob> jobs;
    for (const PlannedJob& job : jobs_)
      if (kept.count(job.id) || references.count(job.id)) jobs.push_back(job);
    jobs_ = std::move(jobs);
  }

  // The shard's plan, for `impactbench merge` to tell a finished shard from one that stopped early.
  // suite: the digest of the whole suite's plan.
  void record_plan(const std::string& suite) const {
    record_shard_plan(settings_.out, ShardPlan{*settings_.shard, suite, planned_job_ids(), planned_step_keys(),
                                               settings_.resume_command});
    // A shard is a suite's folder even when it gets no job (more shards than units): the report reads it.
    if (!fs::exists(settings_.out + "/runs.jsonl")) {
      write_text_file(settings_.out + "/runs.jsonl", "");
      write_text_file(settings_.out + "/runs.csv", csv_header(RunRecord{}));
    }
  }

  // The row a step-search group writes to steps.csv (its probes' job ids are the group's id with /dt=...).
  StepGroup step_group(const PlannedJob& job) const {
    const bool with_chain = !job.chain_reference.empty();
    return StepGroup{job.id, scenarios_[job.scenario].name, to_string(job.spec.settings.law), job.spec.engine,
                     options_text(job.spec.settings.options),
                     with_chain ? "reference on the " + std::to_string(job.chain_links) + "-link chain" : "beam reference",
                     job.chain_links};
  }

  void plan() {
    std::vector<std::string> files;
    for (const std::string& input : settings_.inputs) {
      if (fs::is_directory(input)) {
        for (const std::string& f : find_scenario_files(input)) files.push_back(f);
      } else {
        files.push_back(input);
      }
    }
    std::set<std::string> planned;
    for (const std::string& file : files) {
      try {
        scenarios_.push_back(load_scenario(file));
      } catch (const std::exception& e) {
        unrunnable_.push_back(unrunnable(fs::path(file).stem().string() + "/unreadable", fs::path(file).stem().string(),
                                         file, "", "", e.what()));
        continue;
      }
      const std::size_t index = scenarios_.size() - 1;
      Scenario& s = scenarios_.back();
      const bool cut = settings_.max_duration_s > 0 && s.duration_s > settings_.max_duration_s;
      if (cut) {
        s.duration_s = settings_.max_duration_s;  // the scoring window, the last part of the run, is kept
        s.scoring_window_s = std::min(s.scoring_window_s, s.duration_s);
      }
      if (cut || settings_.measurement.window_s) warn_if_window_in_transient(s, settings_.measurement);
      // The native contact path ignores the scenario's law: its run for the first law answers for all.
      std::optional<ContactLaw> first_law;
      for (ContactLaw law : settings_.laws)
        if (!first_law && s.contact.has(law)) first_law = law;
      for (ContactLaw law : settings_.laws) {
        if (!s.contact.has(law)) {
          unrunnable_.push_back(unrunnable(s.name + "/" + to_string(law) + "/unavailable", s.name, file, "", to_string(law),
                                           "the scenario has no [contact." + std::string(to_string(law)) + "] table"));
          continue;
        }
        PlannedJob beam = make_job(index, JobKind::beam_reference, "reference", law, 0, settings_.reference_options);
        add(beam, planned);
        for (const std::string& engine : settings_.engines) {
          if (engine == "reference") continue;
          const auto engine_options = settings_.engine_options.count(engine) ? settings_.engine_options.at(engine)
                                                                             : std::map<std::string, std::string>{};
          const std::vector<double> steps = settings_.time_steps_s.empty() || settings_.step_search
                                                ? std::vector<double>{0}
                                                : settings_.time_steps_s;
          const std::vector<std::string> paths =
              settings_.contact_paths.empty() ? std::vector<std::string>{""} : settings_.contact_paths;
          for (const std::string& path : paths)
          for (double dt : steps) {
            auto options = engine_options;
            if (!path.empty()) options["contact"] = path;
            PlannedJob job = make_job(index, JobKind::engine, engine, law, dt, options);
            job.beam_reference = beam.id;
            if (auto simulator = settings_.simulators.make(engine)) {
              if (const auto links = simulator->chain_links(s, job.spec.settings)) {
                auto chain_options = settings_.reference_options;
                for (const auto& [name, value] : settings_.simulators.chain_reference_options(*links)) chain_options[name] = value;
                PlannedJob chain = make_job(index, JobKind::chain_reference, "reference", law, 0, chain_options);
                chain.beam_reference = beam.id;
                chain.chain_links = *links;
                job.chain_reference = chain.id;
                job.chain_links = *links;
                add(chain, planned);
              }
            }
            if (settings_.step_search) {
              if (planned.insert(job.id).second) step_groups_.push_back(job);  // its probes are planned by the search
              continue;
            }
            const auto contact = options.find("contact");
            if (contact != options.end() && contact->second == "native" && law != *first_law)
              job.same_run_as = make_job(index, JobKind::engine, engine, *first_law, dt, options).id;
            add(job, planned);
          }
        }
      }
    }
  }

  PlannedJob make_job(std::size_t scenario, JobKind kind, const std::string& engine, ContactLaw law, double dt,
                      const std::map<std::string, std::string>& options) const {
    PlannedJob job;
    job.kind = kind;
    job.scenario = scenario;
    job.spec.scenario_path = scenarios_[scenario].source_path;
    job.spec.engine = engine;
    job.spec.settings.law = law;
    job.spec.settings.time_step_s = dt;
    job.spec.settings.output_rate_hz = settings_.output_rate_hz;
    job.spec.settings.options = options;
    job.id = job_id(scenarios_[scenario].name, job.spec);
    return job;
  }

  // Before a step search starts (its references run first), its probes to come: about a bisection of
  // the whole grid, each costing what a probe at the grid's steps costs on average. The search itself
  // replaces this as it goes (run_step_searches).
  void expect_whole_searches() {
    const std::vector<double> grid = step_grid(*settings_.step_search);
    double steps_per_second = 0;
    for (double dt : grid) steps_per_second += 1.0 / dt / static_cast<double>(grid.size());
    // a bisection, and a last probe for each of the three metrics' brackets beside stability's
    const int probes = static_cast<int>(std::ceil(std::log2(grid.size() + 1.0))) + 3;
    for (const PlannedJob& group : step_groups_) {
      JobWork work = work_of(group);
      work.in_steps = true;
      work.units = scenarios_[group.scenario].duration_s * steps_per_second;
      work.stop_key = "";
      progress_->estimate().expect(group.id, work, probes);
    }
  }

  // A job's work for the remaining-time estimate: its steps (an engine at a given step), else its
  // simulated seconds; jobs of one engine and options cost about the same per unit.
  JobWork work_of(const PlannedJob& job) const {
    const double duration_s = scenarios_[job.scenario].duration_s, dt = job.spec.settings.time_step_s;
    JobWork work;
    work.engine = job.spec.engine;
    work.kind = job.spec.engine + "/" + options_text(job.spec.settings.options);
    work.in_steps = dt > 0;
    work.units = dt > 0 ? duration_s / dt : duration_s;
    work.stop_key = work.kind + "/dt=" + exact_number_text(dt);
    if (!job.same_run_as.empty()) work.units = 0;  // scored from another job's run: no work of its own
    return work;
  }

  // What the suite runs, in one line each, before it starts.
  void describe_plan(int to_run) const {
    std::map<std::string, int> by_engine;
    std::set<std::string> names, laws, steps;
    std::vector<const PlannedJob*> shown;
    for (const auto& job : jobs_)
      if (!recorded_.count(job.id)) shown.push_back(&job);
    for (const auto& group : step_groups_) shown.push_back(&group);
    for (const PlannedJob* planned : shown) {
      const PlannedJob& job = *planned;
      ++by_engine[job.spec.engine];
      const Scenario& s = scenarios_[job.scenario];
      char text[96];
      const MetricSettings window = metric_settings(s, settings_.measurement);
      std::snprintf(text, sizeof text, "%s (%g s, scored from %g s)", s.name.c_str(), s.duration_s, window.window_start_s);
      names.insert(text);
      laws.insert(to_string(job.spec.settings.law));
      if (job.spec.settings.time_step_s > 0) {
        std::snprintf(text, sizeof text, "%g s", job.spec.settings.time_step_s);
        steps.insert(text);
      }
    }
    const auto joined = [](const auto& items) {
      std::string text;
      for (const auto& item : items) text += (text.empty() ? "" : ", ") + item;
      return text.empty() ? std::string("-") : text;
    };
    std::vector<std::string> engines;
    for (const auto& [engine, count] : by_engine) engines.push_back(engine + " " + std::to_string(count));
    if (shown.empty()) return;  // all recorded (a resumed suite that had finished)
    std::fprintf(stderr, "suite: %d jobs to run on %d workers into %s%s\n", to_run, std::max(1, settings_.jobs),
                 settings_.out.c_str(),
                 step_groups_.empty() ? ""
                                      : (", then " + std::to_string(step_groups_.size()) +
                                         " step searches (their probes planned as they go)").c_str());
    std::fprintf(stderr, "  scenarios: %s\n  laws: %s; runs (or step searches) per simulator: %s; steps: %s\n",
                 joined(names).c_str(),
                 joined(laws).c_str(), joined(engines).c_str(), joined(steps).c_str());
    const auto scored = std::count_if(jobs_.begin(), jobs_.end(), [&](const PlannedJob& job) {
      return !job.same_run_as.empty() && !recorded_.count(job.id);
    });
    if (scored > 0)
      std::fprintf(stderr, "  %ld of them scored from the native run of another law (native contact ignores the law)\n",
                   static_cast<long>(scored));
  }

  void add(const PlannedJob& job, std::set<std::string>& planned) {
    if (planned.insert(job.id).second) jobs_.push_back(job);
  }

  // The reference a job is compared with, read from its folder once and kept; null if it did not finish.
  const ReferenceData* reference(const std::string& id, const Scenario& scenario) {
    if (id.empty()) return nullptr;
    auto found = references_.find(id);
    if (found == references_.end()) {
      std::unique_ptr<ReferenceData> data;
      try {
        data = std::make_unique<ReferenceData>(load_reference(settings_.out + "/runs/" + id, scenario, settings_.measurement));
      } catch (const std::exception&) {
        data = nullptr;  // the reference failed: the job is recorded without errors against it
      }
      found = references_.emplace(id, std::move(data)).first;
    }
    return found->second.get();
  }

  void start(const PlannedJob& job) {
    const std::string folder = folder_of(job);
    std::error_code error;
    fs::remove_all(folder, error);  // a previous, unfinished attempt
    fs::create_directories(folder, error);
    if (error) throw OutputError(output_error_text(folder, "create the run folder", error.value()));
    const Scenario& scenario = scenarios_[job.scenario];
    // Load the references in this process, so that the job's process inherits them.
    const ReferenceData* beam = reference(job.beam_reference, scenario);
    const ReferenceData* chain = reference(job.chain_reference, scenario);
    std::vector<ScoredFrom> scored;
    for (const PlannedJob* other : unrecorded_scored_from(job)) {
      const std::string other_folder = folder_of(*other);
      fs::remove_all(other_folder, error);
      fs::create_directories(other_folder, error);
      if (error) throw OutputError(output_error_text(other_folder, "create the run folder", error.value()));
      scored.push_back({other, reference(other->beam_reference, scenario), reference(other->chain_reference, scenario)});
    }
    std::fflush(nullptr);
    int message_pipe[2] = {-1, -1};
    if (pipe2(message_pipe, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("cannot start a job's process: pipe: ") + std::strerror(errno));
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("cannot start a job's process: ") + std::strerror(errno));
    if (pid == 0) {
      become_worker(parent);
      close(message_pipe[0]);
      run_in_child(job, folder, scenario, beam, chain, scored, message_pipe[1]);  // never returns
    }
    close(message_pipe[1]);
    running_.emplace(pid, Running{&job, Clock::now(), false, message_pipe[0]});
    progress_->estimate().start(job.id, progress_->now_s());
  }

  // What a job's folder keeps of its series: a reference always its window (engine runs are compared
  // with it, also on --resume), a step-search probe none unless asked (its summary and events say
  // whether the step is stable and accurate), any other run what --series says.
  Measurement measurement_of(const PlannedJob& job) const {
    Measurement m = settings_.measurement;
    if (job.kind != JobKind::engine && m.series == SeriesOutput::none) m.series = SeriesOutput::window;
    if (job.step_probe && !settings_.keep_probe_series) m.series = SeriesOutput::none;
    return m;
  }

  // The job's process: its output goes to log.txt; its record to row.csv and row.jsonl for the parent.
  [[noreturn]] void run_in_child(const PlannedJob& job, const std::string& folder, const Scenario& scenario,
                                 const ReferenceData* beam, const ReferenceData* chain,
                                 const std::vector<ScoredFrom>& scored, int message_pipe) {
    const int log = open((folder + "/log.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (log >= 0) {
      dup2(log, STDOUT_FILENO);
      dup2(log, STDERR_FILENO);
      close(log);
    }
    RunRecord record;
    ReferenceData run_data;  // the run's metrics and trajectory, for the jobs scored from it
    bool ran = false;
    try {
      record = run_job(scenario, job.spec, measurement_of(job), beam, chain, folder, scored.empty() ? nullptr : &run_data,
                       settings_.simulators.make);
      ran = true;
    } catch (const OutputError& e) {
      send_and_exit(message_pipe, e.what());
    } catch (const std::exception& e) {
      record = unrunnable(job.id, scenario.name, scenario.source_path, job.spec.engine, to_string(job.spec.settings.law),
                          e.what());
      record.time_step_s = job.spec.settings.time_step_s;
      record.options = options_text(job.spec.settings.options);
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
                            other.chain, folder, folder_of(o));
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

  // Waits for a job to end (or stops one past its time limit) and records it; returns the job and the
  // runs.jsonl line recorded for it (none when nothing ended).
  std::optional<std::pair<const PlannedJob*, std::string>> reap(bool block) {
    while (true) {
      int status = 0;
      const pid_t pid = waitpid(-1, &status, WNOHANG);
      if (pid > 0) {
        auto it = running_.find(pid);
        if (it == running_.end()) continue;
        const Running r = it->second;
        running_.erase(it);
        return std::pair{r.job, collect(*r.job, status, r.timed_out, r.message_pipe)};
      }
      const auto now = Clock::now();
      for (auto& [child, r] : running_) {
        if (!r.timed_out && std::chrono::duration<double>(now - r.started).count() > settings_.time_limit_s) {
          r.timed_out = true;
          kill(child, SIGKILL);
        }
      }
      if (!block || running_.empty() || interrupted()) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

  // Records a job that ended; returns its runs.jsonl line ("" when an interruption stopped it: nothing
  // is recorded and --resume reruns it).
  std::string collect(const PlannedJob& job, int status, bool timed_out, int message_pipe) {
    const std::string folder = folder_of(job);
    const std::string output_error = message_pipe >= 0 ? receive(message_pipe) : "";
    if (message_pipe >= 0) close(message_pipe);
    if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerOutputError)
      throw OutputError(output_error.empty() ? output_error_text(folder, "write the run's files", 0) : output_error);
    const bool clean = !timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(folder + "/row.jsonl");
    if (clean) {
      const std::vector<const PlannedJob*> scored = unrecorded_scored_from(job);
      std::string json;
      if (!recorded_.count(job.id)) {
        json = append_row_of(job);
      } else {  // recorded before: run again only for the jobs scored from it
        json = read_file(folder + "/row.jsonl");
        remove_row_files(folder);
      }
      for (const PlannedJob* other : scored) append_row_of(*other);
      return json;
    }
    if (interrupted()) return "";  // stopped by the interruption, not by its own fault: --resume reruns it
    const Scenario& s = scenarios_[job.scenario];
    RunRecord record = unrunnable(job.id, s.name, s.source_path, job.spec.engine, to_string(job.spec.settings.law),
                                  describe_exit(status, settings_.time_limit_s, timed_out, last_line(folder + "/log.txt")));
    record.time_step_s = job.spec.settings.time_step_s;
    record.options = options_text(job.spec.settings.options);
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
  std::vector<const PlannedJob*> unrecorded_scored_from(const PlannedJob& job) const {
    std::vector<const PlannedJob*> jobs;
    const auto [first, last] = scored_from_.equal_range(job.id);
    for (auto it = first; it != last; ++it)
      if (!recorded_.count(it->second->id)) jobs.push_back(it->second);
    return jobs;
  }

  // Appends the record a job's process left in its folder (row.csv, row.jsonl), shows it and returns its
  // runs.jsonl line. The work done, for the cost per step: the steps an engine run took (a job scored
  // from another's run did none of its own, and its time is that run's).
  std::string append_row_of(const PlannedJob& job) {
    const std::string folder = folder_of(job);
    const std::string json = read_file(folder + "/row.jsonl"), csv = read_file(folder + "/row.csv");
    append_rows(settings_.out, csv, json);
    recorded_.insert(job.id);
    // what the progress estimate reads back: the steps taken (fewer than planned when it stopped
    // unstable) and the simulator's own time
    const RecordedRun recorded = read_recorded_run(json);
    const bool own_run = job.same_run_as.empty();
    const double steps = own_run && job.spec.settings.time_step_s > 0 && recorded.steps > 0 ? recorded.steps : -1;
    const double wall_time_s = std::isnan(recorded.wall_time_s) ? -1 : recorded.wall_time_s;
    count_and_show(job.id, recorded.verdict, own_run ? steps : 0, own_run ? wall_time_s : -1);
    remove_row_files(folder);
    return json;
  }

  static void remove_row_files(const std::string& folder) {
    std::error_code error;
    fs::remove(folder + "/row.jsonl", error);
    fs::remove(folder + "/row.csv", error);
  }

  void finish(const RunRecord& record) {
    append_run(settings_.out, record);
    count_and_show(record.job_id, record.verdict);
  }

  void count_and_show(const std::string& id, Verdict verdict, double units_done = -1, double compute_s = -1) {
    ++outcome_.jobs_run;
    if (verdict == Verdict::unstable || verdict == Verdict::failed) ++outcome_.not_ok;
    progress_->estimate().finish(id, progress_->now_s(), units_done, compute_s);
    progress_->job_done(id, verdict, std::max(1, settings_.jobs));
  }

  // --find-steps: each group's search picks its next probe when its previous one has ended; groups
  // share the worker processes. Probes already in runs.jsonl (--resume) are read, not run again.
  void run_step_searches() {
    const StepSearchSettings& search_settings = *settings_.step_search;
    const std::set<std::string> rows_done =
        settings_.resume ? repair_and_list_step_rows(settings_.out) : std::set<std::string>{};
    std::map<std::string, std::string> recorded = recorded_run_lines(settings_.out);  // references and probes
    struct Group {
      const PlannedJob* job;  // the group's job with dt = 0: its id is the group's id
      StepGroup info;
      std::unique_ptr<StepSearch> search;
      bool with_chain = false, running = false, finished = false;
      int probe_index = -1;
    };
    std::vector<Group> groups;
    for (const PlannedJob& job : step_groups_) {
      Group g;
      g.job = &job;
      g.with_chain = !job.chain_reference.empty();
      g.info = step_group(job);
      if (rows_done.count(step_row_key(g.info, search_settings))) {
        progress_->estimate().expect(g.info.group_id, {}, 0);  // recorded before (--resume): nothing to come
        continue;
      }
      const std::string& reference_id = g.with_chain ? job.chain_reference : job.beam_reference;
      const ReferenceFacts facts = recorded.count(reference_id) ? reference_from_json(recorded[reference_id]) : ReferenceFacts{};
      g.search = std::make_unique<StepSearch>(search_settings, facts, g.info.accuracy_reference);
      groups.push_back(std::move(g));
    }
    std::map<std::string, std::size_t> group_of_probe;
    int finished_groups = 0, finished_probes = 0;  // the searches done here: how many probes a search takes
    while (!interrupted()) {  // an interruption leaves the rest to --resume (run() stops the workers)
      for (std::size_t i = 0; i < groups.size(); ++i) {
        Group& g = groups[i];
        if (g.finished || g.running) continue;
        std::optional<int> next;
        PlannedJob probe;
        while ((next = g.search->next_probe())) {
          probe = make_job(g.job->scenario, JobKind::engine, g.job->spec.engine, g.job->spec.settings.law,
                           g.search->grid()[*next], g.job->spec.settings.options);
          probe.beam_reference = g.job->beam_reference;
          probe.chain_reference = g.job->chain_reference;
          probe.chain_links = g.job->chain_links;
          probe.step_probe = true;
          if (!recorded.count(probe.id)) break;
          g.search->add(*next, probe_from_json(recorded[probe.id], g.with_chain));  // run before (--resume)
          ++outcome_.jobs_skipped;
        }
        if (!next) {
          append_step_row(settings_.out, StepRow{g.info, search_settings, g.search.get()});
          g.finished = true;
          ++outcome_.step_searches;
          ++finished_groups;
          finished_probes += g.search->probes();
          progress_->estimate().expect(g.info.group_id, {}, 0);
          continue;
        }
        // The probes still to come, for the remaining time: about a bisection's worth, each costing on
        // average what a probe at the bracket's unprobed steps costs.
        // A bisection's worth at least; as many as the searches that ended needed, where they needed more.
        const int measured_left =
            finished_groups > 0 ? (finished_probes + finished_groups - 1) / finished_groups - g.search->probes() : 0;
        const int probes_left = std::max(g.search->probes_left_estimate(), measured_left);
        JobWork later = work_of(probe);
        later.units = scenarios_[probe.scenario].duration_s * g.search->mean_unprobed_steps_per_second();
        // Their steps differ from this probe's: what share of this step's runs ended early says nothing of them.
        later.stop_key = "expected probes";
        progress_->estimate().expect(g.info.group_id, later, probes_left);
        if (interrupted() || static_cast<int>(running_.size()) >= std::max(1, settings_.jobs)) continue;  // waits for a worker
        progress_->estimate().expect(g.info.group_id, later, probes_left - 1);  // this one is planned below
        probe_jobs_.push_back(probe);
        group_of_probe[probe.id] = i;
        g.probe_index = *next;
        g.running = true;
        progress_->add_to_total(1);
        progress_->estimate().plan(probe.id, work_of(probe));
        start(probe_jobs_.back());
      }
      if (running_.empty()) break;  // every group has finished
      if (const auto ended = reap(true)) {
        const auto found = group_of_probe.find(ended->first->id);
        if (found == group_of_probe.end() || ended->second.empty()) continue;
        Group& g = groups[found->second];
        recorded[ended->first->id] = ended->second;
        g.search->add(g.probe_index, probe_from_json(ended->second, g.with_chain));
        g.running = false;
      }
    }
  }

  const SuiteSettings settings_;  // a copy: the tolerance record is set in it (with_one_tolerance_record)
  std::vector<Scenario> scenarios_;
  std::vector<PlannedJob> jobs_;
  std::vector<PlannedJob> step_groups_;  // --find-steps: one job (dt = 0) per group, not run itself
  std::deque<PlannedJob> probe_jobs_;    // the searches' probes (a deque keeps their addresses)
  std::vector<RunRecord> unrunnable_;
  std::set<std::string> recorded_;
  std::multimap<std::string, const PlannedJob*> scored_from_;  // a run's job id -> the jobs scored from its run
  std::map<std::string, std::unique_ptr<ReferenceData>> references_;
  std::map<pid_t, Running> running_;
  std::unique_ptr<Progress> progress_;
  SuiteOutcome outcome_;
};

}  // namespace

SuiteOutcome run_suite(const SuiteSettings& settings) {
  const InterruptionHandler handler;  // outlives the runner, which stops its workers when it ends
  return SuiteRunner(settings).run();
}

}  // namespace ib
