// The suite's plan (suite_runner.h): the job matrix scenarios x laws x engines x steps, the references
// each job is compared with, and the plan described before the suite starts (its shards: suite_shard.cpp).
#include "harness/suite/suite_runner.h"

#include "harness/scoring/plausibility.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cctype>
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
#include "harness/jobs/progress.h"
#include "harness/records/number_text.h"
#include "harness/records/recorded_run.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

// The row a step-search group writes to steps.csv (its probes' job ids are the group's id with /dt=...).
StepGroup SuiteRunner::step_group(const PlannedJob& job) const {
  const bool with_chain = !job.chain_reference.empty();
  return StepGroup{
      job.id,
      scenarios_[job.scenario].name,
      to_string(job.spec.settings.law),
      job.spec.engine,
      options_text(job.spec.settings.options),
      with_chain ? "reference on the " + std::to_string(job.chain_links) + "-link chain" : "beam reference",
      job.chain_links};
}

// The job id of a scenario file that cannot be read: its stem, made unique by a digest of its path when
// another file of the suite has the same stem, and cut to fit a file name.
static std::string unreadable_job_id(const std::string& file, bool stem_shared) {
  std::string stem = fs::path(file).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') c = '_';
  if (stem.size() > 64 || stem_shared || stem.empty() || stem[0] == '.') {
    std::error_code error;
    const fs::path canonical = fs::weakly_canonical(file, error);
    stem = stem.substr(0, 48) + "-" + plan_digest({error ? file : canonical.string()}).substr(0, 8);
  }
  return stem + "/unreadable";
}

std::vector<PlannedUnit> SuiteRunner::planned_units() {
  plan();
  std::vector<PlannedUnit> units;
  for (const RunRecord& r : unrunnable_) units.push_back({r.job_id, PlannedUnit::Kind::unrunnable, {}, ""});
  const auto unit_of = [](const PlannedJob& job, PlannedUnit::Kind kind) {
    PlannedUnit unit{job.id, kind, {}, job.same_run_as};
    for (const std::string& id : {job.beam_reference, job.chain_reference})
      if (!id.empty()) unit.after.push_back(id);
    return unit;
  };
  for (const PlannedJob& job : jobs_)
    units.push_back(unit_of(job, job.kind == JobKind::beam_reference    ? PlannedUnit::Kind::beam_reference
                                 : job.kind == JobKind::chain_reference ? PlannedUnit::Kind::chain_reference
                                                                        : PlannedUnit::Kind::engine));
  for (const PlannedJob& group : step_groups_) units.push_back(unit_of(group, PlannedUnit::Kind::step_search));
  return units;
}

void SuiteRunner::plan() {
  std::set<std::string> planned;  // a job two parts plan runs once, with the first part's settings
  part_jobs_.resize(parts_.size());
  part_files_.resize(parts_.size());
  for (std::size_t part = 0; part < parts_.size(); ++part) plan_part(part, planned);
  for (const auto* list : {&jobs_, &step_groups_})
    for (const PlannedJob& job : *list)
      for (const std::string& id : {job.beam_reference, job.chain_reference})
        if (!id.empty()) compared_references_.insert(id);
}

void SuiteRunner::plan_part(std::size_t part_index, std::set<std::string>& planned) {
  const SuiteSettings& part = parts_[part_index];
  std::vector<std::string>& part_jobs = part_jobs_[part_index];
  std::vector<std::string> files;
  for (const std::string& input : part.inputs) {
    std::error_code error;
    if (fs::is_directory(input, error)) {
      const std::vector<std::string> found = find_scenario_files(input);
      if (found.empty())
        throw std::invalid_argument(input +
                                    ": holds no scenario file (*.toml, searched recursively); expected scenario "
                                    "files or folders of them");
      files.insert(files.end(), found.begin(), found.end());
    } else if (!fs::exists(input, error)) {
      throw std::invalid_argument(input +
                                  ": no such file or folder; expected scenario files (*.toml) or folders of them");
    } else {
      files.push_back(input);  // a file that cannot be read as a scenario is recorded as such: the others run
    }
  }
  // A file reached twice (a folder and a file in it) is planned once.
  std::set<std::string> seen;
  std::map<std::string, int> stems;
  files.erase(std::remove_if(files.begin(), files.end(),
                             [&seen](const std::string& f) {
                               std::error_code error;
                               const fs::path canonical = fs::weakly_canonical(f, error);
                               return !seen.insert(error ? f : canonical.string()).second;
                             }),
              files.end());
  for (const std::string& file : files) ++stems[fs::path(file).stem().string()];
  part_files_[part_index] = files;
  const auto add_unrunnable = [&](RunRecord record) {
    part_jobs.push_back(record.job_id);
    for (const RunRecord& r : unrunnable_)
      if (r.job_id == record.job_id) return;
    unrunnable_.push_back(std::move(record));
  };
  const auto add_job = [&](const PlannedJob& job) {
    part_jobs.push_back(job.id);
    add(job, planned);
  };
  std::map<std::string, std::string> file_of_name;  // the job ids start with the scenario's name: one file each
  for (const std::string& file : files) {
    try {
      scenarios_.push_back(load_scenario(file));
      scenario_part_.push_back(part_index);
    } catch (const std::exception& e) {
      add_unrunnable(unrunnable(unreadable_job_id(file, stems[fs::path(file).stem().string()] > 1),
                                fs::path(file).stem().string(), file, "", "", e.what()));
      continue;
    }
    const auto [named, fresh] = file_of_name.emplace(scenarios_.back().name, file);
    if (!fresh)
      throw std::invalid_argument(file + ": [scenario] name = \"" + scenarios_.back().name + "\" is also the name of " +
                                  named->second +
                                  "; allowed: a name no other scenario of the suite has (its job ids "
                                  "and run folders are named after it)");
    const std::size_t index = scenarios_.size() - 1;
    Scenario& s = scenarios_.back();
    const bool cut = cut_run(s, part.max_duration_s);
    // A window the user moved into the start-up transient: said now and recorded with every run of the
    // scenario (JobSpec::warnings), the references included; a scenario file's own window is its author's choice.
    std::vector<std::string> warnings;
    if (cut || part.measurement.window_s)
      if (std::string w = warn_if_window_in_transient(s, part.measurement); !w.empty()) warnings.push_back(w);
    // The native contact path ignores the scenario's law: its run for the first law answers for all.
    std::optional<ContactLaw> first_law;
    for (ContactLaw law : part.laws)
      if (!first_law && s.contact.has(law)) first_law = law;
    for (ContactLaw law : part.laws) {
      if (!s.contact.has(law)) {
        add_unrunnable(unrunnable(s.name + "/" + to_string(law) + "/unavailable", s.name, file, "", to_string(law),
                                  "the scenario has no [contact." + std::string(to_string(law)) + "] table"));
        continue;
      }
      // Each start of an ensemble is planned as a run of its own, compared with the references of its start.
      for (int start = 0; start < part.ensemble.reference_starts; ++start) {
        PlannedJob beam = make_job(index, JobKind::beam_reference, "reference", law, 0, part.reference_options, start);
        beam.spec.warnings = warnings;
        add_job(beam);
        for (int links : part.reference_chain_links)
          add_job(chain_reference_job(index, law, start, links, part, beam, warnings));
        for (const std::string& engine : part.engines) {
          if (engine == "reference" || start >= part.ensemble.engine_starts) continue;
          const auto engine_options =
              part.engine_options.count(engine) ? part.engine_options.at(engine) : std::map<std::string, std::string>{};
          for (const auto& [options, dt] :
               engine_configurations(part, settings_.simulators, engine, law, engine_options)) {
            PlannedJob job = make_job(index, JobKind::engine, engine, law, dt, options, start);
            job.spec.warnings = warnings;
            job.beam_reference = beam.id;
            if (auto simulator = settings_.simulators.make(engine)) {
              if (const auto links = simulator->chain_links(s, job.spec.settings)) {
                // the chain's damping is the engine's choice (option chain_damping): its reference is damped alike
                const auto damping = options.find("chain_damping");
                PlannedJob chain = chain_reference_job(index, law, start, *links, part, beam, warnings,
                                                       damping == options.end() ? "" : damping->second);
                job.chain_reference = chain.id;
                job.chain_links = *links;
                add_job(chain);
              }
            }
            if (part.step_search) {
              RunSettings coarsest = job.spec.settings;  // the search's largest step on this scenario
              coarsest.time_step_s = part.step_search->max_step_s;
              check_run_size(s, coarsest);
              if (planned.insert(job.id).second) step_groups_.push_back(job);  // its probes are planned by the search
              continue;
            }
            const auto contact = options.find("contact");
            if (contact != options.end() && contact->second == "native" && law != *first_law)
              job.same_run_as = make_job(index, JobKind::engine, engine, *first_law, dt, options, start).id;
            add_job(job);
          }
        }
      }
    }
  }
}

PlannedJob SuiteRunner::chain_reference_job(std::size_t scenario, ContactLaw law, int start, int links,
                                            const SuiteSettings& part, const PlannedJob& beam,
                                            const std::vector<std::string>& warnings,
                                            const std::string& chain_damping) const {
  auto options = part.reference_options;
  for (const auto& [name, value] : settings_.simulators.chain_reference_options(links)) options[name] = value;
  if (!chain_damping.empty()) options["chain_damping"] = chain_damping;  // the engines' option of that name
  PlannedJob chain = make_job(scenario, JobKind::chain_reference, "reference", law, 0, options, start);
  chain.spec.warnings = warnings;
  chain.beam_reference = beam.id;
  chain.chain_links = links;
  return chain;
}

PlannedJob SuiteRunner::make_job(std::size_t scenario, JobKind kind, const std::string& engine, ContactLaw law,
                                 double dt, const std::map<std::string, std::string>& options, int start) const {
  PlannedJob job;
  const SuiteSettings::Ensemble& ensemble = parts_[scenario_part_[scenario]].ensemble;
  if (start > 0 || ensemble.reference_starts > 1)
    job.spec.start = {start, kind == JobKind::beam_reference ? ensemble.reference_starts : ensemble.engine_starts,
                      start * ensemble.displacement_step_m};
  job.kind = kind;
  job.scenario = scenario;
  job.spec.scenario_path = scenarios_[scenario].source_path;
  job.spec.engine = engine;
  job.spec.settings.law = law;
  job.spec.settings.time_step_s = dt;
  job.spec.settings.output_rate_hz = parts_[scenario_part_[scenario]].output_rate_hz;
  job.spec.settings.options = options;
  job.id = job_id(scenarios_[scenario].name, job.spec);
  return job;
}

// Before a step search starts (its references run first), its probes to come: about a bisection of
// the whole grid, each costing what a probe at the grid's steps costs on average. The search itself
// replaces this as it goes (run_step_searches).
void SuiteRunner::expect_whole_searches() {
  for (const PlannedJob& group : step_groups_) {
    const std::vector<double> grid = step_grid(*part_of(group).step_search);
    double steps_per_second = 0;
    for (double dt : grid) steps_per_second += 1.0 / dt / static_cast<double>(grid.size());
    // a bisection, and a last probe for each of the three metrics' brackets beside stability's
    const int probes = static_cast<int>(std::ceil(std::log2(grid.size() + 1.0))) + 3;
    JobWork work = work_of(group);
    work.in_steps = true;
    work.units = scenarios_[group.scenario].duration_s * steps_per_second;
    work.stop_key = "";
    progress_->estimate().expect(group.id, work, probes);
  }
}

// A job's work for the remaining-time estimate: its steps (an engine at a given step), else its
// simulated seconds; jobs of one engine and options cost about the same per unit.
JobWork SuiteRunner::work_of(const PlannedJob& job) const {
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
void SuiteRunner::describe_plan(int to_run) const {
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
    const ScoringWindow window = scoring_window(s, part_of(job).measurement.window_s);
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
               step_groups_.empty() ? ""
                                    : (", and " + std::to_string(step_groups_.size()) +
                                       " step searches (their probes planned as they go)")
                                          .c_str());
  std::fprintf(stderr, "  scenarios: %s\n  laws: %s; runs (or step searches) per simulator: %s; steps: %s\n",
               joined(names).c_str(), joined(laws).c_str(), joined(engines).c_str(), joined(steps).c_str());
  const auto scored = std::count_if(jobs_.begin(), jobs_.end(), [&](const PlannedJob& job) {
    return !job.same_run_as.empty() && !recorded_.count(job.id);
  });
  if (scored > 0)
    std::fprintf(stderr, "  %ld of them scored from the native run of another law (native contact ignores the law)\n",
                 static_cast<long>(scored));
}

void SuiteRunner::add(const PlannedJob& job, std::set<std::string>& planned) {
  check_run_size(scenarios_[job.scenario], job.spec.settings);  // before anything runs: exit 2, not hours later
  check_scoring_window(scenarios_[job.scenario], part_of(job).measurement);
  if (planned.insert(job.id).second) jobs_.push_back(job);
}

}  // namespace ib::suite_internal

namespace ib {

std::vector<PlannedUnit> plan_suites(const std::vector<SuiteSettings>& parts) {
  return suite_internal::SuiteRunner(parts).planned_units();
}

}  // namespace ib
