// A study's parts placed in its folder and run as one plan on one pool (study.h).
#include "harness/study/study.h"

#include <algorithm>
#include <memory>

#include "harness/jobs/unit_source.h"
#include "harness/jobs/worker_process.h"
#include "harness/records/engines_file.h"

namespace ib {

const char* to_string(StudyPartKind kind) {
  switch (kind) {
    case StudyPartKind::suite:
      return "suite";
    case StudyPartKind::search:
      return "search";
    case StudyPartKind::sweep:
      return "sweep";
    case StudyPartKind::other:
      return "other";
    case StudyPartKind::validation:
      return "validation";
  }
  return "";
}

std::string folder_of(const PartOfItsOwnKind& part, const std::string& name, const StudySettings& settings) {
  return settings.out + "/" + part.kind() + "/" + name;
}

std::vector<StudyPart> place_study_parts(const std::vector<StudyPart>& parts, const StudySettings& settings) {
  std::vector<StudyPart> placed;
  bool first_suite = true;
  for (const StudyPart& given : parts) {
    if (std::find(settings.left_out.begin(), settings.left_out.end(), given.kind) != settings.left_out.end()) continue;
    StudyPart part = given;
    MatrixSettings* shared = nullptr;
    if (auto* sweep = std::get_if<SweepSettings>(&part.settings)) {
      sweep->out = settings.out + "/sweeps/" + part.name;
      shared = sweep;
    } else if (auto* suite = std::get_if<SuiteSettings>(&part.settings)) {
      suite->out = settings.out;
      suite->reference_cache = settings.reference_cache;
      suite->extend = !first_suite;  // the later parts have other settings: each adds its suite to the folder
      first_suite = false;
      shared = suite;
    }
    if (shared) {
      shared->jobs = settings.jobs;
      shared->shard = settings.shard;
      shared->resume = settings.resume;
    }
    placed.push_back(std::move(part));
  }
  return placed;
}

StudyOutcome run_study(const std::vector<StudyPart>& parts, const StudySettings& settings) {
  std::vector<SuiteSettings> suites;
  std::vector<const StudyPart*> sweeps, others;
  const std::vector<StudyPart> placed = place_study_parts(parts, settings);
  for (const StudyPart& part : placed) {
    if (const auto* suite = std::get_if<SuiteSettings>(&part.settings))
      suites.push_back(*suite);
    else
      (std::holds_alternative<SweepSettings>(part.settings) ? sweeps : others).push_back(&part);
  }
  // The suites and searches are one source (a job two parts plan runs once), each other part another; every
  // source is prepared (checked, its folder made) before any unit runs.
  const InterruptionHandler handler;  // outlives the pool, which stops its workers when it ends
  std::unique_ptr<SuiteSource> suite_source = suites.empty() ? nullptr : prepare_suites(suites);
  std::vector<std::unique_ptr<SweepSource>> sweep_sources;
  for (const StudyPart* sweep : sweeps)
    sweep_sources.push_back(prepare_sweep(std::get<SweepSettings>(sweep->settings)));
  std::vector<std::unique_ptr<UnitSource>> other_sources;
  for (const StudyPart* other : others) {
    const auto& own = *std::get<std::shared_ptr<const PartOfItsOwnKind>>(other->settings);
    other_sources.push_back(own.prepare(folder_of(own, other->name, settings), settings));
  }
  std::vector<UnitSource*> sources;
  if (suite_source) sources.push_back(suite_source.get());
  for (const auto& sweep : sweep_sources) sources.push_back(sweep.get());
  for (const auto& other : other_sources) sources.push_back(other.get());
  run_units(sources, settings.jobs);
  StudyOutcome outcome;
  if (suite_source) outcome.suites = with_engines_file(settings.out, suites.front().simulators, suite_source->finish());
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    const SweepSettings& sweep = std::get<SweepSettings>(sweeps[i]->settings);
    outcome.sweeps.push_back(
        {sweeps[i]->name, with_engines_file(sweep.out, sweep.simulators, sweep_sources[i]->finish())});
  }
  for (std::size_t i = 0; i < others.size(); ++i) {
    const auto& own = *std::get<std::shared_ptr<const PartOfItsOwnKind>>(others[i]->settings);
    outcome.others.push_back({others[i]->name, own.finish(*other_sources[i])});
  }
  return outcome;
}

CampaignResult result_of(const StudyOutcome& outcome) {
  CampaignResult result;
  if (outcome.suites) result = worse(result, result_of(end_of(*outcome.suites)));
  for (const StudyOutcome::Sweep& sweep : outcome.sweeps) result = worse(result, result_of(end_of(sweep.outcome)));
  for (const StudyOutcome::Other& other : outcome.others) result = worse(result, result_of(other.end));
  return result;
}

}  // namespace ib
