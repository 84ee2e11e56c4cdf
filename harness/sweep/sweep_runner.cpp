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
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "harness/jobs/campaign_folder.h"
#include "harness/jobs/progress.h"
#include "harness/jobs/shard_plan.h"
#include "harness/jobs/unit_source.h"
#include "harness/jobs/worker_process.h"
#include "harness/records/engines_file.h"
#include "harness/records/folder_lock.h"
#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/sweep/sweep_internal.h"
#include "model/scenario_toml.h"
#include "physics/modal_model.h"

namespace ib {

namespace {

using namespace sweep_internal;

// Everything that decides the sweep's results: a --resume or a shard of another sweep is refused.
nlohmann::ordered_json settings_record(const SweepSettings& s, const Scenario& scenario) {
  nlohmann::ordered_json j;
  j["scenario"] = scenario.name;
  j["scenario_file"] = s.scenario_path;
  // its content (a file of the same name edited between two sweeps is another sweep; compare says so)
  j["scenario_digest"] = plan_digest({read_text_file(s.scenario_path)});
  j["ratios"] = s.ratios;
  std::vector<std::string> starts;
  for (SweepStart start : s.starts) starts.push_back(to_string(start));
  j["starts"] = starts;
  record_configurations(s, j);
  j["continuation_duration_s"] = s.continuation_duration_s;
  j["rest_duration_s"] = s.rest_duration_s.value_or(scenario.duration_s);
  j["window_s"] = s.window_s;
  if (s.ensemble.reference_starts > 1) {  // absent without one: a sweep recorded before ensembles resumes as it was
    j["reference_ensemble_starts"] = s.ensemble.reference_starts;
    j["ensemble_step_m"] = s.ensemble.displacement_step_m;
    j["ensemble_ratios"] = s.ensemble.ratios.empty() ? s.ratios : s.ensemble.ratios;
  }
  j["output_rate_hz"] = s.output_rate_hz;
  j["sensor_rate_hz"] = s.measurement.sensor_rate_hz;
  j["merge_window_s"] = s.measurement.merge_window_s;
  return j;
}

class SweepRunner : public SweepSource {
 public:
  explicit SweepRunner(SweepSettings s) : s_(std::move(s)) {}
  void begin();
  std::optional<double> next_cost() override;
  std::string start_next(ProcessPool& pool) override;
  void ended(const ProcessEnd& end) override;
  void tick(ProcessPool& pool) override;
  SweepOutcome finish() override;

 private:
  struct Running {
    const SweepChain* chain;
    int rows_done = 0;      // when the chain last finished a row (or started): its clock restarts with each row
    double units_left = 0;  // its work not done when it started (the cost model's units)
  };

  std::string folder_of(const SweepRow& row) const { return s_.out + "/runs/" + row.id; }
  std::string log_of(const SweepChain& chain) const { return s_.out + "/runs/" + chain.id + "/log.txt"; }
  int rows_done(const SweepChain& chain) const {
    int done = 0;
    for (const SweepRow& row : chain.rows) done += row_done(folder_of(row)) ? 1 : 0;
    return done;
  }
  // The work of a chain's rows not done yet, in the cost model that suites share (progress.h).
  JobWork work_left(const SweepChain& chain) const;
  double now_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - began_).count(); }
  void prepare_folder();
  [[noreturn]] void run_chain_in_child(const SweepChain& chain, int message_pipe);
  // Rows from..end of a chain that will not run: row `from` with first_reason (and timed_out), the rest
  // with "not run: " + rest_reason.
  void record_rest_not_run(const SweepChain& chain, std::size_t from, const std::string& first_reason,
                           const std::string& rest_reason, bool timed_out);
  void refresh_tables();

  const SweepSettings s_;
  Scenario scenario_;
  std::vector<SweepChain> all_, mine_;
  std::vector<std::string> my_row_ids_;
  // A chain to run, with the work of its rows not done yet (known when the sweep begins: only its own process
  // records its rows).
  struct Pending {
    const SweepChain* chain;
    JobWork work;
  };
  std::vector<Pending> pending_;
  std::size_t next_ = 0;                    // the pending chain next_cost chose, which start_next starts
  std::map<std::string, Running> running_;  // by unit id
  RemainingTime estimate_;                  // the chains' costs, as a suite's jobs' (by chain id)
  std::chrono::steady_clock::time_point began_ = std::chrono::steady_clock::now();
  int recorded_ = -1;  // rows in the tables when last written
  SweepOutcome outcome_;
  std::unique_ptr<FolderLock> lock_;  // the output folder's, held while the sweep writes into it
};

void SweepRunner::prepare_folder() {
  lock_ = open_campaign_folder(s_.out, CampaignKind::sweep);
  const std::string rows = s_.out + "/sweep.jsonl";
  check_same_shard(s_.out, CampaignKind::sweep, s_.shard,
                   std::filesystem::exists(rows) && std::filesystem::file_size(rows) > 0);
  const nlohmann::ordered_json record = settings_record(s_, scenario_);
  const std::string path = s_.out + "/sweep.json";
  refuse_results_without_resume(s_.out, CampaignKind::sweep, s_.resume);
  if (std::filesystem::exists(path)) {
    const auto held = nlohmann::ordered_json::parse(read_text_file(path), nullptr, false);
    if (held.is_discarded())
      throw std::invalid_argument(path + ": not a sweep's settings (not JSON); remove the folder to start again");
    // a sweep recorded before the scenario's digest was kept is resumed on its other settings
    nlohmann::ordered_json now = record;
    if (!held.contains("scenario_digest")) now.erase("scenario_digest");
    const std::string keys = differing_keys(held, now);
    if (!keys.empty()) refuse_other_settings(s_.out, CampaignKind::sweep, keys, "");
  } else {
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

void SweepRunner::run_chain_in_child(const SweepChain& chain, int message_pipe) {
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
    send_and_exit(message_pipe, e.what());
  }
  std::fflush(nullptr);
  _exit(0);
}

JobWork SweepRunner::work_left(const SweepChain& chain) const {
  double simulated_s = 0;
  for (const SweepRow& row : chain.rows)
    if (!row_done(folder_of(row))) simulated_s += row_scenario(scenario_, row, s_).scenario.duration_s;
  const JobSpec& job = chain.rows.front().job;
  return run_work(job.engine, options_text(job.settings.options), job.settings.time_step_s, simulated_s);
}

// The chain to start next as a suite chooses its job (choose_next): a kind not measured yet first, so that its
// cost is known early, then the costliest.
std::optional<double> SweepRunner::next_cost() {
  if (pending_.empty()) return std::nullopt;
  std::vector<JobWork> work;
  for (const Pending& pending : pending_) work.push_back(pending.work);
  const NextUnit chosen = choose_next(estimate_, work);
  next_ = chosen.index;
  return chosen.cost_s;
}

std::string SweepRunner::start_next(ProcessPool& pool) {
  const SweepChain& chain = *pending_[next_].chain;
  const JobWork work = pending_[next_].work;
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(next_));
  estimate_.plan(chain.id, work);
  estimate_.start(chain.id, now_s());
  std::filesystem::create_directories(s_.out + "/runs/" + chain.id);
  const std::string unit = "sweep " + s_.out + " " + chain.id;
  pool.start({unit, s_.time_limit_s, log_of(chain), /*append_log=*/true},
             [this, &chain](int message_pipe) { run_chain_in_child(chain, message_pipe); });
  running_[unit] = Running{&chain, rows_done(chain), work.units};
  return unit;
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

void SweepRunner::ended(const ProcessEnd& end) {
  const SweepChain& chain = *running_.at(end.unit).chain;
  const double units_left_at_start = running_.at(end.unit).units_left;
  running_.erase(end.unit);
  const int status = end.status;
  if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerOutputError)
    throw OutputError(end.output_error.empty() ? last_line(log_of(chain)) : end.output_error);
  estimate_.finish(chain.id, now_s(), units_left_at_start - work_left(chain).units);
  std::size_t first_missing = chain.rows.size();
  for (std::size_t k = 0; k < chain.rows.size() && first_missing == chain.rows.size(); ++k)
    if (!row_done(folder_of(chain.rows[k]))) first_missing = k;
  if (first_missing == chain.rows.size()) return;
  if (interrupted() || stopped_from_outside(status, end.timed_out)) {
    if (!interrupted()) ++outcome_.chains_stopped, outcome_.stopped_by = WTERMSIG(status);
    std::fprintf(stderr, "sweep: %s stopped by signal %d before r = %s; --resume runs it again\n", chain.id.c_str(),
                 WIFSIGNALED(status) ? WTERMSIG(status) : 0, ratio_text(chain.rows[first_missing].ratio).c_str());
    return;
  }
  const std::string why = describe_exit(status, s_.time_limit_s, end.timed_out, last_line(log_of(chain)));
  record_rest_not_run(
      chain, first_missing, why,
      "the chain's process ended at r = " + ratio_text(chain.rows[first_missing].ratio) + " (see that row)",
      end.timed_out);
}

// The time limit is per ratio: a chain's clock restarts with each row it finishes.
void SweepRunner::tick(ProcessPool& pool) {
  for (auto& [unit, run] : running_) {
    const int done = rows_done(*run.chain);
    if (done != run.rows_done) run.rows_done = done, pool.restart_clock(unit);
  }
  refresh_tables();
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

void SweepRunner::begin() {
  scenario_ = load_scenario(s_.scenario_path);
  if (!scenario_.motor)
    throw std::invalid_argument(s_.scenario_path +
                                ": a sweep needs a motor ([motor] in the scenario); this one has none");
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

  for (const SweepChain& chain : mine_) {
    const int done = rows_done(chain);
    outcome_.rows_skipped += done;
    if (done < static_cast<int>(chain.rows.size())) pending_.push_back({&chain, work_left(chain)});
  }
  std::fprintf(stderr, "sweep: %s, %zu ratios x %zu chains%s: %d rows to run (%d recorded already)\n",
               scenario_.name.c_str(), s_.ratios.size(), mine_.size(),
               s_.shard ? (" (shard " + to_string(*s_.shard) + ")").c_str() : "",
               outcome_.rows_total - outcome_.rows_skipped, outcome_.rows_skipped);
}

SweepOutcome SweepRunner::finish() {
  if (interrupted()) outcome_.interrupted_by = interrupt_signal;
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

CampaignEnd end_of(const SweepOutcome& outcome) {
  return {outcome.interrupted_by, outcome.chains_stopped, outcome.stopped_by, outcome.not_ok};
}

std::unique_ptr<SweepSource> prepare_sweep(const SweepSettings& settings) {
  auto runner = std::make_unique<SweepRunner>(settings);
  runner->begin();
  return runner;
}

SweepOutcome run_sweep(const SweepSettings& settings) {
  const InterruptionHandler handler;
  const std::unique_ptr<SweepSource> sweep = prepare_sweep(settings);
  run_units({sweep.get()}, settings.jobs);
  return with_engines_file(settings.out, settings.simulators, sweep->finish());
}

}  // namespace ib
