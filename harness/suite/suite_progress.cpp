// What the suite tells while it runs (suite_runner.h): its plan in a few lines before it starts, and the work
// each job is for the remaining-time estimate.
#include "harness/suite/suite_runner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "harness/records/number_text.h"
#include "harness/scoring/plausibility.h"

namespace ib::suite_internal {

// Before a step search starts (its references run first), its probes to come: about a bisection of
// the whole grid, each costing what a probe at the grid's steps costs on average. The search itself
// replaces this as it goes (run_step_searches).
void SuiteRunner::expect_whole_searches() {
  for (const PlannedJob& group : plan_.step_groups) {
    const std::vector<double> grid = step_grid(*plan_.part_of(group).step_search);
    double steps_per_second = 0;
    for (double dt : grid) steps_per_second += 1.0 / dt / static_cast<double>(grid.size());
    // a bisection, and a last probe for each of the three metrics' brackets beside stability's
    const int probes = static_cast<int>(std::ceil(std::log2(grid.size() + 1.0))) + 3;
    JobWork work = work_of(plan_, group);
    work.in_steps = true;
    work.units = plan_.scenarios[group.scenario].duration_s * steps_per_second;
    work.stop_key = "";
    progress_->estimate().expect(group.id, work, probes);
  }
}

// What the suite runs, in one line each, before it starts.
void SuiteRunner::describe_plan(int to_run) const {
  std::map<std::string, int> by_engine;
  std::set<std::string> names, laws, steps;
  std::vector<const PlannedJob*> shown;
  for (const auto& job : plan_.jobs)
    if (!recorded_.count(job.id)) shown.push_back(&job);
  for (const auto& group : plan_.step_groups) shown.push_back(&group);
  for (const PlannedJob* planned : shown) {
    const PlannedJob& job = *planned;
    ++by_engine[job.spec.engine];
    const Scenario& s = plan_.scenarios[job.scenario];
    char text[96];
    const ScoringWindow window = scoring_window(s, plan_.part_of(job).measurement.window_s);
    std::snprintf(text, sizeof text, "%s (%g s, scored from %g s)", s.name.c_str(), s.duration_s, window.start_s);
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
               plan_.step_groups.empty() ? ""
                                         : (", and " + std::to_string(plan_.step_groups.size()) +
                                            " step searches (their probes planned as they go)")
                                               .c_str());
  std::fprintf(stderr, "  scenarios: %s\n  laws: %s; runs (or step searches) per simulator: %s; steps: %s\n",
               joined(names).c_str(), joined(laws).c_str(), joined(engines).c_str(), joined(steps).c_str());
  const auto scored = std::count_if(plan_.jobs.begin(), plan_.jobs.end(), [&](const PlannedJob& job) {
    return !job.same_run_as.empty() && !recorded_.count(job.id);
  });
  if (scored > 0)
    std::fprintf(stderr, "  %ld of them scored from the native run of another law (native contact ignores the law)\n",
                 static_cast<long>(scored));
}

}  // namespace ib::suite_internal
