#include "harness/suite/step_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "harness/records/number_text.h"
#include "harness/records/recorded_run.h"
#include "harness/scoring/metric_catalog.h"

namespace ib {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string step_text(double dt) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", dt);
  return text;
}

}  // namespace

double tolerance_of(const AccuracyTolerances& tolerances, HeadlineMetric metric) {
  return tolerance_of(scored_metric(to_string(metric)), tolerances);  // the catalog's key and tolerance
}

const char* to_string(HeadlineMetric metric) {
  switch (metric) {
    case HeadlineMetric::frame1_sensor_peak:
      return "frame1_sensor_peak";
    case HeadlineMetric::contact_duration:
      return "contact_duration";
    case HeadlineMetric::impacts_per_cycle:
      return "impacts_per_cycle";
  }
  return "";
}

std::vector<double> step_grid(const StepSearchSettings& s) {
  if (!(s.min_step_s > 0) || !(s.max_step_s >= s.min_step_s) || !std::isfinite(s.max_step_s))
    throw std::invalid_argument("step range " + exact_number_text(s.min_step_s) + "," +
                                exact_number_text(s.max_step_s) + ": allowed: 0 < MIN <= MAX [s]");
  if (s.points_per_octave < 1)
    throw std::invalid_argument("grid points per octave " + std::to_string(s.points_per_octave) + ": allowed: >= 1");
  std::vector<double> grid;
  // dt_k = max 2^(-k/n), computed from k each time (no accumulated rounding), while dt_k >= min
  for (int k = 0;; ++k) {
    const double dt = s.max_step_s * std::exp2(-static_cast<double>(k) / s.points_per_octave);
    if (dt < s.min_step_s * (1 - 1e-12)) break;
    grid.push_back(dt);
    if (grid.size() > 10000) throw std::invalid_argument("step range: more than 10000 grid points");
  }
  return grid;
}

namespace {
double error_of(const HeadlineErrors& e, HeadlineMetric m) {
  switch (m) {
    case HeadlineMetric::frame1_sensor_peak:
      return e.frame1_sensor_peak_relative;
    case HeadlineMetric::contact_duration:
      return e.contact_duration_relative;
    case HeadlineMetric::impacts_per_cycle:
      return e.impacts_per_cycle_difference;
  }
  return kNaN;
}
}  // namespace

ProbeResult probe_from_json(const std::string& json_line, bool with_chain) {
  const RecordedRun recorded = read_recorded_run(json_line);
  ProbeResult r;
  if (!recorded.readable) {
    r.reason = "unreadable record";
    return r;
  }
  r.verdict = recorded.verdict;
  r.reason = recorded.reason;
  r.timed_out = recorded.timed_out;
  r.wall_time_s = recorded.wall_time_s;
  for (HeadlineMetric m : kHeadlineMetrics) {
    r.error[m] = error_of(with_chain ? recorded.vs_chain_reference : recorded.vs_reference, m);
    r.beam_error[m] = error_of(recorded.vs_reference, m);
  }
  return r;
}

ReferenceFacts reference_from_json(const std::string& json_line) {
  const RecordedRun recorded = read_recorded_run(json_line);
  ReferenceFacts f;
  if (!recorded.readable) return f;
  f.finished = recorded.verdict == Verdict::ok || recorded.verdict == Verdict::inaccurate;
  f.frame1_sensor_peak_g = recorded.frame1_sensor_peak_g;
  f.contact_duration_mean_s = recorded.contact_duration_mean_s;
  f.impacts_per_cycle = recorded.impacts_per_cycle;
  return f;
}

// ---- the search -------------------------------------------------------------------------------------

StepSearch::StepSearch(const StepSearchSettings& settings, const ReferenceFacts& reference,
                       const std::string& reference_name)
    : settings_(settings), grid_(step_grid(settings)) {
  for (HeadlineMetric m : kHeadlineMetrics) {
    const int p = static_cast<int>(m);
    if (!reference.finished) {
      not_applicable_[p] = "the " + reference_name + " did not finish";
      continue;
    }
    // A relative error needs a non-zero reference value (metrics.cpp relative_error()).
    const double value = m == HeadlineMetric::frame1_sensor_peak ? reference.frame1_sensor_peak_g
                         : m == HeadlineMetric::contact_duration ? reference.contact_duration_mean_s
                                                                 : reference.impacts_per_cycle;
    if (std::isnan(value) || (m != HeadlineMetric::impacts_per_cycle && value == 0))
      not_applicable_[p] = m == HeadlineMetric::frame1_sensor_peak ? "the " + reference_name + " has no sensor peak"
                           : m == HeadlineMetric::contact_duration
                               ? "the " + reference_name + " has no impacts in the window"
                               : "the scenario has no excitation";
  }
}

std::vector<int> StepSearch::predicates() const {
  std::vector<int> out = {kStability};
  for (HeadlineMetric m : kHeadlineMetrics)
    if (!not_applicable_.count(static_cast<int>(m))) out.push_back(static_cast<int>(m));
  return out;
}

StepSearch::Outcome3 StepSearch::judge(int predicate, const ProbeResult& r) const {
  if (r.timed_out) return Outcome3::undecided;
  // stable: the run's verdict is ok or inaccurate; unstable and failed (the simulator's error, a crash)
  // runs gave no usable trajectory at that step
  const bool stable = r.verdict == Verdict::ok || r.verdict == Verdict::inaccurate;
  if (predicate == kStability) return stable ? Outcome3::pass : Outcome3::fail;
  if (!stable) return Outcome3::fail;
  const HeadlineMetric m = static_cast<HeadlineMetric>(predicate);
  const double error = r.error.count(m) ? r.error.at(m) : kNaN;
  // NaN while the reference has the metric: the run lacks it (e.g. no impacts), which is a failure
  return std::abs(error) <= tolerance_of(settings_.tolerance, m) ? Outcome3::pass : Outcome3::fail;
}

Bracket StepSearch::bracket(int predicate) const {
  Bracket b;
  if (not_applicable_.count(predicate)) {
    b.not_applicable = true;
    b.why_not_applicable = not_applicable_.at(predicate);
    return b;
  }
  // The smallest step that failed bounds the search: a pass at a larger step than a failure is not
  // trusted (errors that cancel by chance at one long step are common) and is noted instead.
  for (const auto& [index, result] : results_)
    if (judge(predicate, result) == Outcome3::fail && (!b.fail || index > *b.fail)) b.fail = index;
  for (const auto& [index, result] : results_)
    if (judge(predicate, result) == Outcome3::pass && (!b.fail || index > *b.fail) && (!b.pass || index < *b.pass))
      b.pass = index;
  return b;
}

std::optional<int> StepSearch::unprobed_inside(const Bracket& b) const {
  const int lo = b.fail ? *b.fail : -1, hi = b.pass ? *b.pass : static_cast<int>(grid_.size());
  // The grid index nearest the bracket's middle that has not been probed. A probe that reached the
  // time limit decides nothing, and a smaller step costs more: steps below it are not tried.
  int end = hi;
  for (const auto& [index, result] : results_)
    if (result.timed_out) end = std::min(end, index);
  const double middle = 0.5 * (lo + end);
  std::optional<int> best;
  for (int k = lo + 1; k < end; ++k)
    if (!results_.count(k) && (!best || std::abs(k - middle) < std::abs(*best - middle))) best = k;
  return best;
}

bool StepSearch::closed(const Bracket& b) const { return b.not_applicable || !unprobed_inside(b); }

int StepSearch::probes_left_estimate() const {
  if (settings_.walk) return next_walk_probe() ? settings_.walk_flat_probes : 0;  // at least the flat probes
  int most = 0, open = 0;
  for (int p : predicates()) {
    const Bracket b = bracket(p);
    if (!unprobed_inside(b)) continue;
    ++open;
    int unprobed = 0;
    for (int k = (b.fail ? *b.fail : -1) + 1; k < (b.pass ? *b.pass : static_cast<int>(grid_.size())); ++k)
      unprobed += results_.count(k) ? 0 : 1;
    most = std::max(most, static_cast<int>(std::ceil(std::log2(unprobed + 1.0))));
  }
  // The widest bracket's bisection, and about one probe more for each other open bracket (each tends to
  // need its own last probe).
  return open > 0 ? most + open - 1 : 0;
}

double StepSearch::mean_unprobed_steps_per_second() const {
  if (settings_.walk) {  // the next walk_flat_probes grid steps
    const auto next = next_walk_probe();
    if (!next) return 0;
    double sum = 0;
    int count = 0;
    for (int k = *next; k < std::min<int>(*next + settings_.walk_flat_probes, grid_.size()); ++k, ++count)
      sum += 1.0 / grid_[k];
    return sum / count;
  }
  double widest_sum = 0;
  int widest = -1, widest_count = 0;
  for (int p : predicates()) {
    const Bracket b = bracket(p);
    if (!unprobed_inside(b)) continue;
    const int lo = b.fail ? *b.fail : -1, hi = b.pass ? *b.pass : static_cast<int>(grid_.size());
    double sum = 0;
    int count = 0;
    for (int k = lo + 1; k < hi; ++k)
      if (!results_.count(k)) {
        sum += 1.0 / grid_[k];
        ++count;
      }
    if (hi - lo > widest) {
      widest = hi - lo;
      widest_sum = sum;
      widest_count = count;
    }
  }
  return widest_count > 0 ? widest_sum / widest_count : 0;
}

double beam_score(const ProbeResult& result, const AccuracyTolerances& tolerances) {
  double score = kNaN;
  for (HeadlineMetric m : kHeadlineMetrics) {
    const auto error = result.beam_error.find(m);
    if (error == result.beam_error.end() || std::isnan(error->second)) continue;
    const double multiple = std::abs(error->second) / tolerance_of(tolerances, m);
    if (std::isnan(score) || multiple > score) score = multiple;
  }
  return score;
}

bool StepSearch::walk_stopped_falling() const {
  std::optional<double> best;
  int flat = 0;
  for (const auto& [index, result] : results_) {  // largest step first
    if (judge(kStability, result) != Outcome3::pass) continue;
    const double score = beam_score(result, settings_.tolerance);
    if (!std::isnan(score) && (!best || score < *best - settings_.walk_gain)) {
      best = score;
      flat = 0;
    } else {
      if (!std::isnan(score) && score < *best) best = score;
      ++flat;  // a stable probe without a score cannot show the error falling either
    }
  }
  return flat >= settings_.walk_flat_probes;
}

std::optional<int> StepSearch::next_walk_probe() const {
  if (results_.empty()) return 0;
  const auto& [last, result] = *results_.rbegin();
  if (result.timed_out || last + 1 >= static_cast<int>(grid_.size()) || walk_stopped_falling()) return std::nullopt;
  return last + 1;
}

std::optional<int> StepSearch::next_probe() const {
  if (settings_.walk) return next_walk_probe();
  std::optional<int> next;
  int widest = -1;
  for (int p : predicates()) {
    const Bracket b = bracket(p);
    const auto inside = unprobed_inside(b);
    if (!inside) continue;
    const int width = (b.pass ? *b.pass : static_cast<int>(grid_.size())) - (b.fail ? *b.fail : -1);
    if (width > widest) {
      widest = width;
      next = inside;
    }
  }
  return next;
}

void StepSearch::add(int index, const ProbeResult& result) {
  if (index < 0 || index >= static_cast<int>(grid_.size()))
    throw std::out_of_range("step search: grid index out of range");
  results_[index] = result;
}

StepSearch::Outcome StepSearch::outcome(int predicate) const {
  Outcome o{"", kNaN, kNaN, kNaN, kNaN};
  const Bracket b = bracket(predicate);
  if (b.not_applicable) {
    o.status = "not applicable: " + b.why_not_applicable;
    return o;
  }
  const int last = static_cast<int>(grid_.size()) - 1;
  if (b.pass) o.largest_pass_step_s = grid_[*b.pass];
  if (b.fail) o.smallest_fail_step_s = grid_[*b.fail];
  if (b.pass && predicate != kStability) {
    const ProbeResult& r = results_.at(*b.pass);
    const HeadlineMetric m = static_cast<HeadlineMetric>(predicate);
    o.error_at_largest_pass = r.error.count(m) ? r.error.at(m) : kNaN;
    o.beam_error_at_largest_pass = r.beam_error.count(m) ? r.beam_error.at(m) : kNaN;
  }
  // A walk probes every grid step down to where it stopped: a bracket still open there never passed.
  if (settings_.walk && unprobed_inside(b) && !next_walk_probe())
    o.status = "fails down to the walk's smallest step";
  else if (unprobed_inside(b))
    o.status = "search not finished";
  else if (b.pass && *b.pass == 0)
    o.status = "holds at the largest step";
  else if (!b.pass && b.fail && *b.fail == last)
    o.status = "fails at the smallest step";
  else if (b.pass && b.fail && *b.pass - *b.fail == 1)
    o.status = "bracketed to one grid step";
  else
    o.status = "not decided: probes reached the time limit";
  return o;
}

StepSearch::Outcome StepSearch::stability() const { return outcome(kStability); }
StepSearch::Outcome StepSearch::accuracy(HeadlineMetric metric) const { return outcome(static_cast<int>(metric)); }

std::vector<std::string> StepSearch::notes() const {
  std::vector<std::string> notes;
  // Non-monotone: a pass at a larger step than a failure. The bracket ends at the smallest failing
  // step (the result is a step below which every probe passed); the passes above it are reported here.
  for (int p : predicates()) {
    const Bracket b = bracket(p);
    if (!b.fail) continue;
    std::string above;
    for (const auto& [index, result] : results_)
      if (index < *b.fail && judge(p, result) == Outcome3::pass)
        above += (above.empty() ? "" : ", ") + step_text(grid_[index]);
    if (above.empty()) continue;
    const std::string what =
        p == kStability ? "stable" : std::string(to_string(static_cast<HeadlineMetric>(p))) + " within tolerance";
    notes.push_back("non-monotone: " + what + " at the larger " + above + " s but not at " + step_text(grid_[*b.fail]) +
                    " s");
  }
  for (const auto& [index, result] : results_) {
    if (result.timed_out)
      notes.push_back("not decided at " + step_text(grid_[index]) +
                      " s: the probe reached the time limit (smaller steps not tried)");
    else if (result.verdict == Verdict::failed) {
      const std::string reason = result.reason.size() > 160 ? result.reason.substr(0, 160) + "..." : result.reason;
      notes.push_back("failed at " + step_text(grid_[index]) + " s (counted as not stable): " + reason);
    }
  }
  return notes;
}

double StepSearch::probes_wall_time_s() const {
  double total = 0;
  for (const auto& [index, result] : results_)
    if (std::isfinite(result.wall_time_s)) total += result.wall_time_s;
  return total;
}

std::string StepSearch::probe_list() const {
  std::string list;
  for (const auto& [index, result] : results_)
    list += (list.empty() ? "" : ";") + step_text(grid_[index]) + ":" +
            (result.timed_out ? "timed_out" : to_string(result.verdict));
  return list;
}

}  // namespace ib
