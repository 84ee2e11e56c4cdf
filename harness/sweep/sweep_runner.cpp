// The sweep's chains in worker processes: resume, shards, time limits, signals (sweep.h).
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "harness/records/engines_file.h"
#include "harness/records/folder_lock.h"
#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/sweep/sweep_internal.h"
#include "harness/jobs/worker_process.h"
#include "model/scenario_toml.h"
#include "physics/modal_model.h"

namespace ib {

namespace {

using namespace sweep_internal;
using Clock = std::chrono::steady_clock;

// Everything that decides the sweep's results: a --resume or a shard of another sweep is refused.
nlohmann::ordered_json settings_record(const SweepSettings& s, const Scenario& scenario) {
  nlohmann::ordered_json j;
  j["scenario"] = scenario.name;
  j["scenario_file"] = s.scenario_path;
  j["ratios"] = s.ratios;
  std::vector<std::string> starts, laws;
  for (SweepStart start : s.starts) starts.push_back(to_string(start));
  for (ContactLaw law : s.laws) laws.push_back(to_string(law));
  j["starts"] = starts;
  j["engines"] = s.engines;
  j["laws"] = laws;
  j["contact_paths"] = s.contact_paths;
  j["time_steps_s"] = s.time_steps_s;
  j["reference_options"] = s.reference_options;
  j["engine_options"] = s.engine_options;
  j["continuation_duration_s"] = s.continuation_duration_s;
  j["rest_duration_s"] = s.rest_duration_s.value_or(scenario.duration_s);
  j["window_s"] = s.window_s;
  j["output_rate_hz"] = s.output_rate_hz;
  j["sensor_rate_hz"] = s.measurement.sensor_rate_hz;
  j["merge_window_s"] = s.measurement.merge_window_s;
  return j;
}

class SweepRunner {
 public:
  explicit SweepRunner(const SweepSettings& s) : s_(s) {}
  ~SweepRunner() { stop_all(); }
  SweepOutcome run();

 private:
  struct Running {
    const SweepChain* chain;
    Clock::time_point progress;  // when the chain last finished a row (or started)
    int rows_done = 0;
    bool timed_out = false;
  };

  std::string folder_of(const SweepRow& row) const { return s_.out + "/runs/" + row.id; }
  std::string log_of(const SweepChain& chain) const { return s_.out + "/runs/" + chain.id + "/log.txt"; }
  int rows_done(const SweepChain& chain) const {
    int done = 0;
    for (const SweepRow& row : chain.rows) done += row_done(folder_of(row)) ? 1 : 0;
    return done;
  }
  void prepare_folder();
  [[noreturn]] void run_chain_in_child(const SweepChain& chain);
  void start(const SweepChain& chain);
  void collect(pid_t pid, int status);
  // Rows from..end of a chain that will not run: row `from` with first_reason (and timed_out), the rest
  // with "not run: " + rest_reason.
  void record_rest_not_run(const SweepChain& chain, std::size_t from, const std::string& first_reason,
                           const std::string& rest_reason, bool timed_out);
  void refresh_tables();
  void stop_all();

  const SweepSettings& s_;
  Scenario scenario_;
  std::vector<SweepChain> all_, mine_;
  std::vector<std::string> my_row_ids_;
  std::map<pid_t, Running> running_;
  int recorded_ = -1;  // rows in the tables when last written
  SweepOutcome outcome_;
  std::unique_ptr<FolderLock> lock_;  // the output folder's, held while the sweep writes into it
};

void SweepRunner::prepare_folder() {
  std::error_code error;
  std::filesystem::create_directories(s_.out + "/runs", error);
  if (error) throw OutputError(output_error_text(s_.out, "create the sweep's folder", error.value()));
  lock_ = std::make_unique<FolderLock>(s_.out, "sweep");
  const nlohmann::ordered_json record = settings_record(s_, scenario_);
  const std::string path = s_.out + "/sweep.json";
  if (std::filesystem::exists(path)) {
    if (!s_.resume) throw std::invalid_argument(s_.out + " holds a sweep already (sweep.json); continue it with --resume or choose another --out");
    const auto held = nlohmann::ordered_json::parse(read_text_file(path), nullptr, false);
    if (held.is_discarded()) throw std::invalid_argument(path + ": not a sweep's settings (not JSON); remove the folder to start again");
    const std::string keys = differing_keys(held, record);
    if (!keys.empty())
      throw std::invalid_argument(s_.out + " holds a sweep with other settings (" + keys + " differ, see " + path +
                                  "): --resume continues the same sweep only; choose another --out");
  } else {
    if (std::filesystem::exists(s_.out + "/runs.jsonl")) throw std::invalid_argument(s_.out + " holds a suite; choose another --out for a sweep");
    replace_text_file(path, record.dump(2) + "\n");
  }
  std::vector<std::string> all_ids;
  for (const SweepChain& chain : all_)
    for (const SweepRow& row : chain.rows) all_ids.push_back(row.id);
  std::string plan;
  for (const std::string& id : all_ids) plan += id + "\n";
  replace_text_file(s_.out + "/sweep_plan.txt", plan);
  if (s_.shard) {
    ShardPlan shard;
    shard.shard = *s_.shard;
    all_ids.push_back(record.dump());  // two sweeps of the same rows but other settings are other sweeps
    shard.suite = plan_digest(all_ids);
    shard.jobs = my_row_ids_;
    shard.resume_command = s_.resume_command;
    record_shard_plan(s_.out, shard);
  }
}

void SweepRunner::run_chain_in_child(const SweepChain& chain) {
  std::optional<SavedState> state;
  try {
    for (std::size_t k = 0; k < chain.rows.size(); ++k) {
      const SweepRow& row = chain.rows[k];
      const std::string folder = folder_of(row);
      if (row_done(folder)) {
        state = read_row_state(folder);
        continue;
      }
      if (!row.first_of_chain && !state) {  // the previous ratio ended without a state to continue from
        const std::string why = "the continuation ended at r = " + ratio_text(chain.rows[k - 1].ratio) +
                                " without a state to continue from (see that row's verdict)";
        record_rest_not_run(chain, k, "not run: " + why, why, false);
        break;
      }
      state = run_sweep_row(scenario_, row, s_, state, folder);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::fflush(stderr);
    _exit(kWorkerOutputError);
  }
  std::fflush(nullptr);
  _exit(0);
}

void SweepRunner::start(const SweepChain& chain) {
  std::filesystem::create_directories(s_.out + "/runs/" + chain.id);
  std::fflush(nullptr);
  const pid_t pid = fork_worker();
  if (pid < 0) throw std::runtime_error("cannot start a worker process (fork failed)");
  if (pid == 0) {
    const int log = open(log_of(chain).c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (log >= 0) dup2(log, STDOUT_FILENO), dup2(log, STDERR_FILENO), close(log);
    run_chain_in_child(chain);
  }
  running_[pid] = Running{&chain, Clock::now(), rows_done(chain), false};
}

void SweepRunner::record_rest_not_run(const SweepChain& chain, std::size_t from, const std::string& first_reason,
                                      const std::string& rest_reason, bool timed_out) {
  for (std::size_t k = from; k < chain.rows.size(); ++k) {
    const std::string folder = folder_of(chain.rows[k]);
    if (row_done(folder)) continue;
    record_row_not_run(scenario_, chain.rows[k], s_, folder, k == from ? first_reason : "not run: " + rest_reason,
                       k == from && timed_out);
  }
}

void SweepRunner::collect(pid_t pid, int status) {
  const Running run = running_.at(pid);
  running_.erase(pid);
  const SweepChain& chain = *run.chain;
  if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerOutputError)
    throw OutputError(last_line(log_of(chain)));
  std::size_t first_missing = chain.rows.size();
  for (std::size_t k = 0; k < chain.rows.size() && first_missing == chain.rows.size(); ++k)
    if (!row_done(folder_of(chain.rows[k]))) first_missing = k;
  if (first_missing == chain.rows.size()) return;
  if (interrupted() || stopped_from_outside(status, run.timed_out)) {
    if (!interrupted()) ++outcome_.chains_stopped, outcome_.stopped_by = WTERMSIG(status);
    std::fprintf(stderr, "sweep: %s stopped by signal %d before r = %s; --resume runs it again\n", chain.id.c_str(),
                 WIFSIGNALED(status) ? WTERMSIG(status) : 0, ratio_text(chain.rows[first_missing].ratio).c_str());
    return;
  }
  const std::string why = describe_exit(status, s_.time_limit_s, run.timed_out,
                                                        last_line(log_of(chain)));
  record_rest_not_run(chain, first_missing, why,
                      "the chain's process ended at r = " + ratio_text(chain.rows[first_missing].ratio) + " (see that row)",
                      run.timed_out);
}

void SweepRunner::refresh_tables() {
  int done = 0;
  for (const SweepChain& chain : mine_) done += rows_done(chain);
  if (done == recorded_) return;
  // progress: one line per newly finished row of a running chain
  write_sweep_tables(s_.out, my_row_ids_);
  std::fprintf(stderr, "sweep: %d of %d ratios recorded in %s/sweep.csv\n", done, outcome_.rows_total, s_.out.c_str());
  recorded_ = done;
}

void SweepRunner::stop_all() {
  for (auto& [pid, run] : running_) kill(pid, SIGKILL);
  for (auto& [pid, run] : running_) waitpid(pid, nullptr, 0);
  running_.clear();
}

SweepOutcome SweepRunner::run() {
  scenario_ = load_scenario(s_.scenario_path);
  if (!scenario_.motor)
    throw std::invalid_argument(s_.scenario_path + ": a sweep needs a motor ([motor] in the scenario); this one has none");
  if (s_.ratios.empty()) throw std::invalid_argument("--ratios: no ratio to run");
  for (ContactLaw law : s_.laws)
    if (!scenario_.contact.has(law))
      throw std::invalid_argument(s_.scenario_path + ": law " + to_string(law) + " has no parameters in the scenario");
  all_ = plan_sweep(s_, scenario_.name);
  for (std::size_t c = 0; c < all_.size(); ++c)
    if (!s_.shard || in_shard(c, *s_.shard)) mine_.push_back(all_[c]);
  for (const SweepChain& chain : mine_)
    for (const SweepRow& row : chain.rows) my_row_ids_.push_back(row.id);
  outcome_.rows_total = static_cast<int>(my_row_ids_.size());
  prepare_folder();

  std::vector<const SweepChain*> pending;
  for (const SweepChain& chain : mine_) {
    const int done = rows_done(chain);
    outcome_.rows_skipped += done;
    if (done < static_cast<int>(chain.rows.size())) pending.push_back(&chain);
  }
  std::fprintf(stderr, "sweep: %s, %zu ratios x %zu chains%s: %d rows to run (%d recorded already)\n",
               scenario_.name.c_str(), s_.ratios.size(), mine_.size(),
               s_.shard ? (" (shard " + to_string(*s_.shard) + ")").c_str() : "", outcome_.rows_total - outcome_.rows_skipped,
               outcome_.rows_skipped);
  const InterruptionHandler handler;
  std::size_t next = 0;
  while ((next < pending.size() || !running_.empty()) && !interrupted()) {
    while (next < pending.size() && static_cast<int>(running_.size()) < s_.jobs) start(*pending[next++]);
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running_.count(pid)) {
      collect(pid, status);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    for (auto& [worker, run] : running_) {  // the time limit is per ratio: a chain's clock restarts with each row
      const int done = rows_done(*run.chain);
      if (done != run.rows_done) run.rows_done = done, run.progress = Clock::now();
      if (!run.timed_out && std::chrono::duration<double>(Clock::now() - run.progress).count() > s_.time_limit_s) {
        run.timed_out = true;
        kill(worker, SIGKILL);
      }
    }
    refresh_tables();
  }
  if (interrupted()) {
    outcome_.interrupted_by = interrupt_signal;
    for (auto& [pid, run] : running_) kill(pid, SIGKILL);
    while (!running_.empty()) {  // a row that ended before the stop is kept (row.json is written last)
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (pid < 0) break;
      running_.erase(pid);
    }
  }
  recorded_ = -1;
  refresh_tables();
  int done = 0;
  for (const SweepChain& chain : mine_) done += rows_done(chain);
  outcome_.rows_run = done - outcome_.rows_skipped;
  // not_ok over every recorded row, so that a resumed sweep's exit code covers all its results
  const auto table = read_text_file(s_.out + "/sweep.jsonl");
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    const auto row = nlohmann::json::parse(line, nullptr, false);
    if (row.is_object() && row.value("verdict", "") != "ok") ++outcome_.not_ok;
  }
  return outcome_;
}

}  // namespace

SweepOutcome run_sweep(const SweepSettings& settings) {
  SweepRunner runner(settings);
  return with_engines_file(settings.out, settings.simulators, runner.run());
}

}  // namespace ib
