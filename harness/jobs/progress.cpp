#include "harness/jobs/progress.h"

#include "harness/records/number_text.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <vector>

namespace ib {

JobWork run_work(const std::string& engine, const std::string& options_text, double dt_s, double simulated_s) {
  JobWork work;
  work.engine = engine;
  work.kind = engine + "/" + options_text;
  work.in_steps = dt_s > 0;
  work.units = dt_s > 0 ? simulated_s / dt_s : simulated_s;
  work.stop_key = work.kind + "/dt=" + exact_number_text(dt_s);
  return work;
}

void RemainingTime::plan(const std::string& id, const JobWork& work) { jobs_[id].work = work; }

void RemainingTime::start(const std::string& id, double now_s) {
  const auto job = jobs_.find(id);
  if (job == jobs_.end()) return;
  job->second.started_s = now_s;
  started_kinds_.insert(job->second.work.kind);
}

void RemainingTime::finish(const std::string& id, double now_s, double units_done, double compute_s) {
  const auto found = jobs_.find(id);
  if (found == jobs_.end() || found->second.finished) return;
  Job& job = found->second;
  job.finished = true;
  if (job.started_s < 0 || !(job.work.units > 0)) return;  // recorded without running: nothing measured
  const double seconds = std::max(0.0, now_s - job.started_s);
  const double units = units_done >= 0 ? units_done : job.work.units;
  // Without the simulator's own time, the whole job counts as its work (no overhead measured).
  const double work_s = compute_s >= 0 ? std::min(compute_s, seconds) : seconds;
  if (compute_s >= 0) {
    overhead_.seconds += seconds - work_s;
    overhead_.units += 1;
  }
  for (Sum* sum : {&by_kind_[job.work.kind], &by_engine_[job.work.engine], &by_unit_[job.work.in_steps]}) {
    sum->seconds += work_s;
    sum->units += units;
  }
  Sum& share = share_run_[job.work.stop_key.empty() ? job.work.kind : job.work.stop_key];
  share.seconds += std::min(units, job.work.units);
  share.units += job.work.units;
}

double RemainingTime::likely_units(const JobWork& work) const {
  const auto share = share_run_.find(work.stop_key.empty() ? work.kind : work.stop_key);
  if (share == share_run_.end() || !(share->second.units > 0)) return work.units;
  return work.units * share->second.seconds / share->second.units;
}

double RemainingTime::cost_per_unit(const JobWork& work) const {
  for (const auto& [sums, key] : {std::pair{&by_kind_, &work.kind}, std::pair{&by_engine_, &work.engine}}) {
    const auto sum = sums->find(*key);
    if (sum != sums->end() && sum->second.units > 0) return sum->second.seconds / sum->second.units;
  }
  // A kind not measured yet: the mean over every job measured in the same unit (a first guess).
  const Sum& same_unit = by_unit_[work.in_steps];
  return same_unit.units > 0 ? same_unit.seconds / same_unit.units : -1;
}

void RemainingTime::expect(const std::string& key, const JobWork& work, int count) {
  if (count > 0)
    expected_[key] = {work, count};
  else
    expected_.erase(key);
}

bool RemainingTime::measured(const std::string& kind) const {
  const auto sum = by_kind_.find(kind);
  return sum != by_kind_.end() && sum->second.units > 0;
}

bool RemainingTime::started_kind(const std::string& kind) const { return started_kinds_.count(kind) > 0; }

double RemainingTime::cost_s(const JobWork& work) const {
  const double per_unit = cost_per_unit(work);
  if (per_unit < 0) return -1;
  const double overhead_s = overhead_.units > 0 ? overhead_.seconds / overhead_.units : 0;
  return work.units > 0 ? overhead_s + per_unit * likely_units(work) : 0;
}

double RemainingTime::remaining_s(double now_s, int workers) const {
  // Each job's remaining seconds; a running job has spent some of its own already.
  std::vector<double> left;
  for (const auto& [id, job] : jobs_) {
    if (job.finished) continue;
    const double cost = cost_s(job.work);
    if (cost < 0) return -1;
    left.push_back(job.started_s >= 0 ? std::max(0.0, cost - (now_s - job.started_s)) : cost);
  }
  for (const auto& [key, expected] : expected_) {
    const double cost = cost_s(expected.first);
    if (cost < 0) return -1;
    for (int k = 0; k < expected.second; ++k) left.push_back(cost);
  }
  // The workers share the work; the longest job alone bounds it from below.
  double total = 0, longest = 0;
  for (double s : left) {
    total += s;
    longest = std::max(longest, s);
  }
  return std::max(total / std::max(1, workers), longest);
}

std::size_t next_to_start(const RemainingTime& estimate, const std::vector<JobWork>& pending) {
  std::size_t best = 0;
  double best_cost = -2;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    if (!estimate.measured(pending[i].kind) && !estimate.started_kind(pending[i].kind)) return i;
    const double cost = estimate.cost_s(pending[i]);
    if (cost > best_cost) {
      best = i;
      best_cost = cost;
    }
  }
  return best;
}

NextUnit choose_next(const RemainingTime& estimate, const std::vector<JobWork>& pending) {
  const std::size_t index = next_to_start(estimate, pending);
  const double cost_s = estimate.cost_s(pending[index]);
  return {index, cost_s < 0 ? kUnknownCost : cost_s};
}

namespace {

std::string clock_text(double seconds) {
  if (seconds < 0) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

Progress::Progress(int jobs_to_run)
    : total_(jobs_to_run), start_(std::chrono::steady_clock::now()), terminal_(isatty(STDERR_FILENO)) {}

double Progress::now_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::job_done(const std::string& id, Verdict verdict, int workers) {
  ++done_;
  const double elapsed = now_s();
  const double left = estimate_.remaining_s(elapsed, workers);
  if (terminal_) {
    const int width = 30, filled = total_ > 0 ? std::min(width, width * done_ / total_) : width;
    std::fprintf(stderr, "\r\033[K[%s%s] %d/%d  elapsed %s  left %s  %s: %s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done_, total_, clock_text(elapsed).c_str(),
                 clock_text(left).c_str(), id.c_str(), to_string(verdict));
    if (done_ == total_) std::fputc('\n', stderr);
  } else {
    std::fprintf(stderr, "suite: %d/%d done, elapsed %s, left %s: %s %s\n", done_, total_, clock_text(elapsed).c_str(),
                 clock_text(left).c_str(), id.c_str(), to_string(verdict));
  }
  std::fflush(stderr);
}

}  // namespace ib
