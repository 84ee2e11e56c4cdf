// The suite's plan (suite_plan.h): the job matrix scenarios x laws x engines x steps x ensemble starts, the
// references each job is compared with, and the units of work it makes (its shards: suite_shard.cpp).
#include "harness/suite/suite_plan.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "harness/jobs/shard_plan.h"
#include "harness/records/number_text.h"
#include "harness/records/reporters.h"
#include "harness/scoring/plausibility.h"
#include "model/scenario_toml.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;

namespace {

// The job id of a scenario file that cannot be read: its stem, made unique by a digest of its path when
// another file of the suite has the same stem, and cut to fit a file name.
std::string unreadable_job_id(const std::string& file, bool stem_shared) {
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

// A job into the plan, once: checked before anything runs (exit 2 now, not hours later).
void add(SuitePlan& plan, const PlannedJob& job, std::set<std::string>& planned) {
  check_run_size(plan.scenarios[job.scenario], job.spec.settings);
  check_scoring_window(plan.scenarios[job.scenario], plan.part_of(job).measurement);
  if (planned.insert(job.id).second) plan.jobs.push_back(job);
}

// The reference on the `links`-link chain (damped as an engine's option chain_damping says; "": the
// default), compared with the beam reference `beam` of the same scenario, law and start.
PlannedJob chain_reference_job(const SuitePlan& plan, std::size_t scenario, ContactLaw law, int start, int links,
                               const SuiteSettings& part, const PlannedJob& beam,
                               const std::vector<std::string>& warnings, const std::string& chain_damping = "") {
  auto options = part.reference_options;
  for (const auto& [name, value] : plan.shared().simulators.chain_reference_options(links)) options[name] = value;
  if (!chain_damping.empty()) options["chain_damping"] = chain_damping;  // the engines' option of that name
  PlannedJob chain = make_job(plan, scenario, JobKind::chain_reference, "reference", law, 0, options, start);
  chain.spec.warnings = warnings;
  chain.beam_reference = beam.id;
  chain.chain_links = links;
  return chain;
}

// A job of a part: its id among the part's (also when an earlier part planned it), the job into the plan once.
void add_to_part(SuitePlan& plan, std::size_t part, const PlannedJob& job, std::set<std::string>& planned) {
  plan.part_jobs[part].push_back(job.id);
  add(plan, job, planned);
}

void add_unrunnable_to_part(SuitePlan& plan, std::size_t part, RunRecord record) {
  plan.part_jobs[part].push_back(record.job_id);
  for (const RunRecord& r : plan.unrunnable)
    if (r.job_id == record.job_id) return;
  plan.unrunnable.push_back(std::move(record));
}

// A part's scenario files in the order given, folders searched recursively, a file reached twice (a folder
// and a file in it) once. A file that cannot be read as a scenario stays: it is planned as unrunnable.
std::vector<std::string> scenario_files(const SuiteSettings& part) {
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
      files.push_back(input);
    }
  }
  std::set<std::string> seen;
  files.erase(std::remove_if(files.begin(), files.end(),
                             [&seen](const std::string& f) {
                               std::error_code error;
                               const fs::path canonical = fs::weakly_canonical(f, error);
                               return !seen.insert(error ? f : canonical.string()).second;
                             }),
              files.end());
  return files;
}

// One engine's jobs for one law and ensemble start of the plan's scenario `index`: a run per configuration,
// compared with the beam reference `beam` and with the reference on the engine's own chain; a step search's
// group instead of its runs. The native contact path ignores the law: its run for `first_law` answers for all.
void plan_engine_runs(SuitePlan& plan, std::size_t part_index, std::size_t index, const std::string& engine,
                      ContactLaw law, ContactLaw first_law, int start, const PlannedJob& beam,
                      const std::vector<std::string>& warnings, std::set<std::string>& planned) {
  const SuiteSettings& part = plan.parts[part_index];
  const Scenario& s = plan.scenarios[index];
  const auto engine_options =
      part.engine_options.count(engine) ? part.engine_options.at(engine) : std::map<std::string, std::string>{};
  for (const auto& [options, dt] : engine_configurations(part, plan.shared().simulators, engine, law, engine_options)) {
    PlannedJob job = make_job(plan, index, JobKind::engine, engine, law, dt, options, start);
    job.spec.warnings = warnings;
    job.beam_reference = beam.id;
    if (auto simulator = plan.shared().simulators.make(engine)) {
      if (const auto links = simulator->chain_links(s, job.spec.settings)) {
        // the chain's damping is the engine's choice (option chain_damping): its reference is damped alike
        const auto damping = options.find("chain_damping");
        PlannedJob chain = chain_reference_job(plan, index, law, start, *links, part, beam, warnings,
                                               damping == options.end() ? "" : damping->second);
        job.chain_reference = chain.id;
        job.chain_links = *links;
        add_to_part(plan, part_index, chain, planned);
      }
    }
    if (part.step_search) {
      RunSettings coarsest = job.spec.settings;  // the search's largest step on this scenario
      coarsest.time_step_s = part.step_search->max_step_s;
      check_run_size(s, coarsest);
      if (planned.insert(job.id).second) plan.step_groups.push_back(job);  // its probes are planned by the search
      continue;
    }
    const auto contact = options.find("contact");
    if (contact != options.end() && contact->second == "native" && law != first_law)
      job.same_run_as = make_job(plan, index, JobKind::engine, engine, first_law, dt, options, start).id;
    add_to_part(plan, part_index, job, planned);
  }
}

// The jobs of the plan's scenario `index`, loaded from `file` for the part: for each law it has parameters for
// and each ensemble start (each compared with the references of its start), the beam reference, the
// reference chains, and every engine's runs.
void plan_scenario(SuitePlan& plan, std::size_t part_index, std::size_t index, const std::string& file,
                   std::set<std::string>& planned) {
  const SuiteSettings& part = plan.parts[part_index];
  Scenario& s = plan.scenarios[index];
  const bool cut = cut_run(s, part.max_duration_s);
  // A window the user moved into the start-up transient: said now and recorded with every run of the
  // scenario (JobSpec::warnings), the references included; a scenario file's own window is its author's choice.
  std::vector<std::string> warnings;
  if (cut || part.measurement.window_s)
    if (std::string w = plan.quiet ? window_in_transient_warning(s, part.measurement)
                                   : warn_if_window_in_transient(s, part.measurement);
        !w.empty())
      warnings.push_back(w);
  std::optional<ContactLaw> first_law;
  for (ContactLaw law : part.laws)
    if (!first_law && s.contact.has(law)) first_law = law;
  for (ContactLaw law : part.laws) {
    if (!s.contact.has(law)) {
      add_unrunnable_to_part(
          plan, part_index,
          unrunnable(s.name + "/" + to_string(law) + "/unavailable", s.name, file, "", to_string(law),
                     "the scenario has no [contact." + std::string(to_string(law)) + "] table"));
      continue;
    }
    for (int start = 0; start < part.ensemble.reference_starts; ++start) {
      PlannedJob beam =
          make_job(plan, index, JobKind::beam_reference, "reference", law, 0, part.reference_options, start);
      beam.spec.warnings = warnings;
      add_to_part(plan, part_index, beam, planned);
      for (int links : part.reference_chain_links)
        add_to_part(plan, part_index, chain_reference_job(plan, index, law, start, links, part, beam, warnings),
                    planned);
      for (const std::string& engine : part.engines)
        if (engine != "reference" && start < part.ensemble.engine_starts)
          plan_engine_runs(plan, part_index, index, engine, law, *first_law, start, beam, warnings, planned);
    }
  }
}

// A part's scenarios loaded (and cut) and their jobs planned.
void plan_part(SuitePlan& plan, std::size_t part_index, std::set<std::string>& planned) {
  const std::vector<std::string> files = scenario_files(plan.parts[part_index]);
  std::map<std::string, int> stems;
  for (const std::string& file : files) ++stems[fs::path(file).stem().string()];
  plan.part_files[part_index] = files;
  std::map<std::string, std::string> file_of_name;  // the job ids start with the scenario's name: one file each
  for (const std::string& file : files) {
    try {
      plan.scenarios.push_back(load_scenario(file));
      plan.scenario_part.push_back(part_index);
    } catch (const std::exception& e) {
      add_unrunnable_to_part(plan, part_index,
                             unrunnable(unreadable_job_id(file, stems[fs::path(file).stem().string()] > 1),
                                        fs::path(file).stem().string(), file, "", "", e.what()));
      continue;
    }
    const std::string& name = plan.scenarios.back().name;
    const auto [named, fresh] = file_of_name.emplace(name, file);
    if (!fresh)
      throw std::invalid_argument(file + ": [scenario] name = \"" + name + "\" is also the name of " + named->second +
                                  "; allowed: a name no other scenario of the suite has (its job ids "
                                  "and run folders are named after it)");
    plan_scenario(plan, part_index, plan.scenarios.size() - 1, file, planned);
  }
}

}  // namespace

PlannedJob make_job(const SuitePlan& plan, std::size_t scenario, JobKind kind, const std::string& engine,
                    ContactLaw law, double dt, const std::map<std::string, std::string>& options, int start) {
  PlannedJob job;
  const SuiteSettings::Ensemble& ensemble = plan.parts[plan.scenario_part[scenario]].ensemble;
  if (start > 0 || ensemble.reference_starts > 1)
    job.spec.start = {start, kind == JobKind::beam_reference ? ensemble.reference_starts : ensemble.engine_starts,
                      start * ensemble.displacement_step_m};
  job.kind = kind;
  job.scenario = scenario;
  job.spec.scenario_path = plan.scenarios[scenario].source_path;
  job.spec.engine = engine;
  job.spec.settings.law = law;
  job.spec.settings.time_step_s = dt;
  job.spec.settings.output_rate_hz = plan.parts[plan.scenario_part[scenario]].output_rate_hz;
  job.spec.settings.options = options;
  job.id = job_id(plan.scenarios[scenario].name, job.spec);
  return job;
}

// The row a step-search group writes to steps.csv (its probes' job ids are the group's id with /dt=...).
StepGroup step_group(const SuitePlan& plan, const PlannedJob& job) {
  const bool with_chain = !job.chain_reference.empty();
  return StepGroup{
      job.id,
      plan.scenarios[job.scenario].name,
      to_string(job.spec.settings.law),
      job.spec.engine,
      options_text(job.spec.settings.options),
      with_chain ? "reference on the " + std::to_string(job.chain_links) + "-link chain" : "beam reference",
      job.chain_links};
}

SuitePlan plan_suite(const std::vector<SuiteSettings>& parts, bool quiet) {
  SuitePlan plan;
  plan.quiet = quiet;
  plan.parts = with_one_tolerance_record(parts);
  std::set<std::string> planned;  // a job two parts plan runs once, with the first part's settings
  plan.part_jobs.resize(plan.parts.size());
  plan.part_files.resize(plan.parts.size());
  for (std::size_t part = 0; part < plan.parts.size(); ++part) plan_part(plan, part, planned);
  for (const auto* list : {&plan.jobs, &plan.step_groups})
    for (const PlannedJob& job : *list)
      for (const std::string& id : {job.beam_reference, job.chain_reference})
        if (!id.empty()) plan.compared_references.insert(id);
  return plan;
}

// A job's work for the remaining-time estimate: its steps (an engine at a given step), else its
// simulated seconds; jobs of one engine and options cost about the same per unit.
JobWork work_of(const SuitePlan& plan, const PlannedJob& job) {
  JobWork work = run_work(job.spec.engine, options_text(job.spec.settings.options), job.spec.settings.time_step_s,
                          plan.scenarios[job.scenario].duration_s);
  if (!job.same_run_as.empty()) work.units = 0;  // scored from another job's run: no work of its own
  return work;
}

std::vector<PlannedUnit> planned_units(const SuitePlan& plan) {
  std::vector<PlannedUnit> units;
  for (const RunRecord& r : plan.unrunnable) units.push_back({r.job_id, PlannedUnit::Kind::unrunnable, {}, ""});
  const auto unit_of = [](const PlannedJob& job, PlannedUnit::Kind kind) {
    PlannedUnit unit{job.id, kind, {}, job.same_run_as};
    for (const std::string& id : {job.beam_reference, job.chain_reference})
      if (!id.empty()) unit.after.push_back(id);
    return unit;
  };
  for (const PlannedJob& job : plan.jobs)
    units.push_back(unit_of(job, job.kind == JobKind::beam_reference    ? PlannedUnit::Kind::beam_reference
                                 : job.kind == JobKind::chain_reference ? PlannedUnit::Kind::chain_reference
                                                                        : PlannedUnit::Kind::engine));
  for (const PlannedJob& group : plan.step_groups) units.push_back(unit_of(group, PlannedUnit::Kind::step_search));
  return units;
}

}  // namespace ib::suite_internal

namespace ib {

std::vector<PlannedUnit> plan_suites(const std::vector<SuiteSettings>& parts) {
  return suite_internal::planned_units(suite_internal::plan_to_run(parts));
}

}  // namespace ib
