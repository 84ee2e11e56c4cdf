// The step searches' driver (suite_runner.h): each group's bisection (step_search.h) picks its next probe
// when its previous one has ended; the groups share the worker processes.
#include "harness/suite/suite_runner.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/records/run_files.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

// --find-steps: each group's search picks its next probe when its previous one has ended; groups
// share the worker processes. Probes already in runs.jsonl (--resume) are read, not run again.
void SuiteRunner::run_step_searches() {
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
    if (reference_stopped(job)) {  // its reference was stopped from outside: the search waits for --resume
      ++outcome_.jobs_stopped;
      progress_->estimate().expect(g.info.group_id, {}, 0);
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
        probe.spec.warnings = g.job->spec.warnings;
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

}  // namespace ib::suite_internal
