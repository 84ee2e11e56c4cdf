// The step searches' driver (suite_runner.h): each group's bisection or walk (step_search.h) starts when its
// reference has ended and picks its next probe when its previous one has ended; the probes share the one
// runner's processes with every other job. Probes already in runs.jsonl (--resume) are read, not run again,
// and so is a probe that is a job of the plan (the same id: a walk through a suite part's steps), once it ends.
#include "harness/suite/suite_runner.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "harness/records/run_files.h"

namespace ib::suite_internal {

void SuiteRunner::begin_step_searches() {
  if (plan_.step_groups.empty()) return;
  if (settings_.resume) searches_.rows_done = repair_and_list_step_rows(settings_.out);
  searches_.recorded_lines = recorded_run_lines(settings_.out);
  for (const PlannedJob& job : plan_.jobs) searches_.planned_ids.insert(job.id);
  for (const PlannedJob& job : plan_.step_groups) {
    SearchGroup g;
    g.job = &job;
    g.settings = &*plan_.part_of(job).step_search;
    g.with_chain = !job.chain_reference.empty();
    g.info = step_group(plan_, job);
    if (searches_.rows_done.count(step_row_key(g.info, *g.settings))) {
      progress_->estimate().expect(g.info.group_id, {}, 0);  // recorded before (--resume): nothing to come
      continue;
    }
    searches_.groups.push_back(std::move(g));
  }
}

// The first group, in planned order, whose next probe can start: its reference has ended and its previous probe
// too. A group whose search needs no more probes writes its row to steps.csv here.
SuiteRunner::SearchGroup* SuiteRunner::ready_search() {
  searches_.awaited.clear();
  for (SearchGroup& g : searches_.groups) {
    if (g.finished || g.running) continue;
    if (g.next_probe) return &g;
    if (!references_ended(*g.job)) continue;
    if (!g.search) {
      if (reference_stopped(*g.job)) {  // its reference was stopped from outside: the search waits for --resume
        ++outcome_.jobs_stopped;
        progress_->estimate().expect(g.info.group_id, {}, 0);
        g.finished = true;
        continue;
      }
      const std::string& reference_id = g.with_chain ? g.job->chain_reference : g.job->beam_reference;
      const auto found = searches_.recorded_lines.find(reference_id);
      const ReferenceFacts facts =
          found != searches_.recorded_lines.end() ? reference_from_json(found->second) : ReferenceFacts{};
      g.search = std::make_unique<StepSearch>(*g.settings, facts, g.info.accuracy_reference);
    }
    std::optional<int> next;
    PlannedJob probe;
    while ((next = g.search->next_probe())) {
      probe = make_job(plan_, g.job->scenario, JobKind::engine, g.job->spec.engine, g.job->spec.settings.law,
                       g.search->grid()[*next], g.job->spec.settings.options);
      probe.beam_reference = g.job->beam_reference;
      probe.chain_reference = g.job->chain_reference;
      probe.chain_links = g.job->chain_links;
      probe.spec.warnings = g.job->spec.warnings;
      probe.step_probe = true;
      const auto found = searches_.recorded_lines.find(probe.id);
      if (found == searches_.recorded_lines.end()) break;
      // recorded before (--resume), or the run of a job the plan holds (a walk's ladder crosses the steps a
      // suite part runs): not run again
      g.search->add(*next, probe_from_json(found->second, g.with_chain));
      if (!searches_.planned_ids.count(probe.id)) ++outcome_.jobs_skipped;
    }
    if (next && unfinished_.count(probe.id)) {  // a job of the plan is this probe: its record, once it ends
      searches_.awaited.insert(probe.id);       // (next_cost starts it before other jobs)
      continue;
    }
    if (!next) {
      append_step_row(settings_.out, StepRow{g.info, *g.settings, g.search.get()});
      g.finished = true;
      ++outcome_.step_searches;
      ++searches_.finished;
      searches_.finished_probes += g.search->probes();
      progress_->estimate().expect(g.info.group_id, {}, 0);
      continue;
    }
    // The probes still to come, for the remaining time: a bisection's worth at least; as many as the searches
    // that ended needed, where they needed more; each costing on average what a probe at the bracket's
    // unprobed steps costs (their steps differ from this probe's: what share of this step's runs ended early
    // says nothing of them).
    const int measured_left =
        searches_.finished > 0
            ? (searches_.finished_probes + searches_.finished - 1) / searches_.finished - g.search->probes()
            : 0;
    const int probes_left = std::max(g.search->probes_left_estimate(), measured_left);
    JobWork later = work_of(plan_, probe);
    later.units = plan_.scenarios[probe.scenario].duration_s * g.search->mean_unprobed_steps_per_second();
    later.stop_key = "expected probes";
    progress_->estimate().expect(g.info.group_id, later, probes_left - 1);  // this one is planned when it starts
    g.probe_index = *next;
    g.next_probe = probe;
    return &g;
  }
  return nullptr;
}

void SuiteRunner::probe_ended(const PlannedJob& probe, const std::string& json) {
  SearchGroup& g = searches_.groups[searches_.group_of_probe.at(probe.id)];
  g.running = false;
  if (json.empty()) {  // stopped by an interruption or from outside: the search waits for --resume
    g.finished = true;
    return;
  }
  searches_.recorded_lines[probe.id] = json;
  g.search->add(g.probe_index, probe_from_json(json, g.with_chain));
}

}  // namespace ib::suite_internal
