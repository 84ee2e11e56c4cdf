// The largest stable and the largest accurate time step of each engine configuration, found by
// bisection over the step (issue 8). A group is one (scenario, law, engine, options): its probes are
// ordinary suite jobs at steps of a fixed geometric grid, dt_k = max * 2^(-k / points_per_octave),
// k = 0 .. K (K the last index with dt_k >= min), so that job ids are reproducible and --resume reuses
// every probe already recorded. Each predicate (stable; each headline metric within its tolerance)
// keeps a bracket between its largest passing and its smallest failing step; every probe updates all
// brackets, and the next probe is the middle of the widest bracket still open. step_search.cpp holds the
// search logic, steps_file.cpp the steps.csv / steps.jsonl rows, and the suite's step_search_driver.cpp
// runs the probes.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "harness/jobs/worker_process.h"   // kTimeLimitReason
#include "harness/records/recorded_run.h"  // recorded_run_lines: the probes and references recorded
#include "harness/scoring/verdict.h"

namespace ib {

// The headline metrics whose largest accurate step is searched, in column order.
enum class HeadlineMetric { frame1_sensor_peak, contact_duration, impacts_per_cycle };
constexpr std::array<HeadlineMetric, 3> kHeadlineMetrics = {
    HeadlineMetric::frame1_sensor_peak, HeadlineMetric::contact_duration, HeadlineMetric::impacts_per_cycle};
const char* to_string(HeadlineMetric metric);  // "frame1_sensor_peak", "contact_duration", "impacts_per_cycle"

struct StepSearchSettings {
  double min_step_s = 1e-6;   // the grid's smallest step is the last one >= this [s]
  double max_step_s = 1e-3;   // the grid's largest step [s]
  int points_per_octave = 4;  // grid steps per halving of the step (ratio 2^(1/4) = 1.19)
  // A front's ladder instead of a bisection (issue 32, --step-walk): walk down the grid from its largest
  // step, one grid step at a time, until the error against the beam stops falling (walk_flat_probes stable
  // probes in a row that lower the smallest score so far by at most walk_gain; a score is the largest
  // headline error over its tolerance), the grid ends, or a probe reaches the time limit (smaller steps cost
  // more). The gain is a tenth of a tolerance: 1 % of error at the default 10 %.
  bool walk = false;
  double walk_gain = 0.1;
  int walk_flat_probes = 2;
  // "Within tolerance" is what the verdict calls accurate: the suite's verdict tolerances
  // (Measurement::verdicts.accuracy, set by --tolerance), which run_suite copies here. Intended change
  // of issue 17: the search once had its own stricter defaults (5 % peak, 10 % duration, 0.05 impacts
  // per cycle), so a default search now brackets at the verdict's 10 % / 0.10 and runs other probes.
  AccuracyTolerances tolerance;
};
// A headline metric's tolerance: relative for the sensor peak and the mean contact duration, absolute
// for impacts per cycle.
double tolerance_of(const AccuracyTolerances& tolerances, HeadlineMetric metric);

// The grid, largest step first. Throws std::invalid_argument unless 0 < min <= max and points >= 1.
std::vector<double> step_grid(const StepSearchSettings& settings);

// One probe as the search sees it, read from its runs.jsonl record.
struct ProbeResult {
  Verdict verdict = Verdict::failed;
  std::string reason;
  bool timed_out = false;  // stopped at the time limit: not decided
  double wall_time_s = 0;  // the simulator's cost [s]
  // errors against the accuracy reference (the engine's own chain, else the beam), and the beam's
  std::map<HeadlineMetric, double> error, beam_error;  // NaN: not measured
};

// A probe's score against the beam: its largest headline error over that metric's tolerance (the report's
// score, without the log decrement, which the probes do not carry); NaN when it has none.
double beam_score(const ProbeResult& result, const AccuracyTolerances& tolerances);

// The facts of a reference run that decide whether a metric can be judged at all.
struct ReferenceFacts {
  bool finished = false;               // a record with verdict ok
  double frame1_sensor_peak_g = 0;     // NaN when absent
  double contact_duration_mean_s = 0;  // NaN without impacts in the window
  double impacts_per_cycle = 0;        // NaN without excitation
};

// Reads a probe from its runs.jsonl line. with_chain: judge against vs_chain_reference_* (the engine
// builds a chain), else vs_reference_*.
ProbeResult probe_from_json(const std::string& json_line, bool with_chain);
ReferenceFacts reference_from_json(const std::string& json_line);

// A predicate's bracket over grid indices (0 = the largest step). fail: the largest index (smallest
// step) that failed; pass: the smallest index beyond it that passed, so that every probe at a smaller
// step passed too. Closed when adjacent, when it holds at the largest step, or when it fails at the
// smallest. Passes at larger steps than a failure (non-monotone) are noted, not used.
struct Bracket {
  std::optional<int> pass, fail;
  bool not_applicable = false;
  std::string why_not_applicable;
};

// The search of one group: feed it probe results, ask it for the next step.
class StepSearch {
 public:
  // accuracy_reference: the reference the errors are judged against; its missing metrics are not applicable.
  StepSearch(const StepSearchSettings& settings, const ReferenceFacts& accuracy_reference,
             const std::string& reference_name);

  const std::vector<double>& grid() const { return grid_; }
  // The next grid index to probe; none when every bracket is closed or cannot be narrowed further (a
  // walk: when it has stopped).
  std::optional<int> next_probe() const;
  void add(int index, const ProbeResult& result);
  bool probed(int index) const { return results_.count(index) > 0; }
  // About how many more probes the search needs: a bisection of its widest open bracket's unprobed
  // grid points and one more per other open bracket (a remaining-time estimate, not a promise).
  int probes_left_estimate() const;
  // The mean of 1 / step over the unprobed grid points of the widest open bracket [1/s]: a later
  // probe's steps per simulated second, on average (the smaller steps cost the most); 0 when none.
  double mean_unprobed_steps_per_second() const;
  int probes() const { return static_cast<int>(results_.size()); }

  // What the search found, with the notes (non-monotone outcomes, probes not decided).
  struct Outcome {
    std::string status;                // see predicate_status()
    double largest_pass_step_s;        // NaN: none in range
    double smallest_fail_step_s;       // NaN: none in range
    double error_at_largest_pass = 0;  // metrics: the error there (accuracy reference), and vs the beam
    double beam_error_at_largest_pass = 0;
  };
  Outcome stability() const;
  Outcome accuracy(HeadlineMetric metric) const;
  std::vector<std::string> notes() const;
  double probes_wall_time_s() const;
  std::string probe_list() const;  // "step [s]:verdict;...", largest step first (column probe_outcomes)

 private:
  enum class Outcome3 { pass, fail, undecided };
  static constexpr int kStability = -1;  // predicate keys: -1 stability, else the metric's index
  Outcome3 judge(int predicate, const ProbeResult& r) const;
  std::optional<int> next_walk_probe() const;
  bool walk_stopped_falling() const;  // the last walk_flat_probes stable probes did not lower the best score
  Bracket bracket(int predicate) const;
  bool closed(const Bracket& b) const;
  std::optional<int> unprobed_inside(const Bracket& b) const;  // the next probe inside b, if any
  Outcome outcome(int predicate) const;
  std::vector<int> predicates() const;

  StepSearchSettings settings_;
  std::vector<double> grid_;
  std::map<int, std::string> not_applicable_;  // predicate -> why
  std::map<int, ProbeResult> results_;         // grid index -> result
};

// steps.csv / steps.jsonl: one row per group.
struct StepGroup {
  std::string group_id;  // scenario/engine/law[/options]: the probes' job ids without dt
  std::string scenario, law, engine, options, accuracy_reference;
  int chain_links = 0;
};
struct StepRow {
  StepGroup group;
  StepSearchSettings settings;
  const StepSearch* search = nullptr;
};
std::string steps_csv_header();
std::string steps_csv_row(const StepRow& row);
std::string steps_json_line(const StepRow& row);
// Appends one row to DIR/steps.csv and DIR/steps.jsonl, flushed at once. Throws OutputError (run_files.h) naming the
// file.
void append_step_row(const std::string& folder, const StepRow& row);
// The key a group's row is found by on --resume: its id, range, grid and tolerances.
std::string step_row_key(const StepGroup& group, const StepSearchSettings& settings);
// A steps.jsonl line read back as a struct: the one decoder of a row (--resume, merge).
struct RecordedStepRow {
  bool readable = false;  // false: not a row (a line a kill cut short); nothing else is set
  std::string group_id;
  std::string key;  // step_row_key of the row's group and settings
};
RecordedStepRow read_step_row(const std::string& json_line);
// For --resume: drops a steps.jsonl line a kill cut short, rewrites steps.csv from steps.jsonl, and
// returns the keys of the rows recorded.
std::set<std::string> repair_and_list_step_rows(const std::string& folder);

}  // namespace ib
