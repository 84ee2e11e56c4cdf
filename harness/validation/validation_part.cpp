// The validation part of a study (validation_part.h).
#include "harness/validation/validation_part.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "harness/study/study_cost.h"
#include "harness/validation/input_sample.h"
#include "model/scenario_toml.h"

namespace ib {

ValidationPart::ValidationPart(ValidationSettings settings) : settings_(std::move(settings)) {
  if (settings_.points < 1)
    throw std::invalid_argument("points " + std::to_string(settings_.points) + ": allowed: an integer >= 1");
}

std::unique_ptr<UnitSource> ValidationPart::prepare(const std::string& folder, const StudySettings& study) const {
  std::filesystem::create_directories(folder);
  std::vector<SuiteSettings> parts = {settings_.sample, settings_.nominal, settings_.tight};
  parts[0].inputs =
      write_input_sample(settings_.inputs, settings_.sample.inputs, settings_.points, folder).scenario_files;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    parts[i].out = folder;
    parts[i].extend = i > 0;  // each adds its suite to the folder, as a study's later suites do
    parts[i].jobs = study.jobs;
    parts[i].shard = study.shard;
    parts[i].resume = study.resume;
    parts[i].reference_cache = study.reference_cache;
  }
  return prepare_suites(parts);
}

std::string ValidationPart::plan(const std::string& folder) const {
  std::ostringstream line;
  line << settings_.points << " points of " << settings_.inputs.path << " (" << settings_.inputs.inputs.size()
       << " inputs) x " << settings_.sample.inputs.size() << " cases, the reference alone, the nominal cases from "
       << settings_.nominal.ensemble.reference_starts << " starts and at tight tolerances beside -> " << folder;
  return line.str();
}

std::optional<PartOfItsOwnKind::Work> ValidationPart::planned_work() const {
  Work work;
  const int runs_per_case = settings_.points + settings_.nominal.ensemble.reference_starts + 1;
  for (const std::string& file : settings_.sample.inputs) {
    Scenario scenario;
    try {
      scenario = load_scenario(file);
    } catch (const std::exception&) {  // the study refused it already (the plan is made after the check)
      continue;
    }
    if (settings_.sample.max_duration_s > 0) cut_run(scenario, settings_.sample.max_duration_s);
    work.runs += runs_per_case;
    const auto cpu_s = estimated_cpu_s(settings_.sample.simulators, "reference", settings_.sample.reference_options, 0,
                                       scenario.duration_s);
    work.cpu_s += runs_per_case * cpu_s.value_or(0);
  }
  return work;
}

CampaignEnd ValidationPart::finish(UnitSource& source) const {
  return end_of(static_cast<SuiteSource&>(source).finish());
}

}  // namespace ib
