// A study file's [[validation]] parts (study_validation.h).
#include "cli/study_validation.h"

#include <filesystem>
#include <memory>

#include "harness/records/run_files.h"
#include "harness/validation/input_sample.h"
#include "harness/validation/validation_part.h"
#include "model/scenario_toml.h"
#include "model/uncertain_inputs.h"

namespace cli {

namespace fs = std::filesystem;
using ib::toml_schema::Checker;

// A [[validation]]'s own keys beyond a suite's: its inputs file and sample size.
void read_validation_keys(const Checker& checker, GivenKeys& given, const std::string& dotted, PartOptions& part) {
  require_folder_name(checker, given, part, dotted, "OUT/validation/");
  require_key(checker, given, part, dotted, "inputs", "an uncertain-inputs file (scenarios/paper_inputs.toml)");
  part.inputs = scenario_path(part.file, given["inputs"]);
  if (given.count("points")) part.points = std::stoi(given["points"]);
  if (given.count("nominal_starts")) part.nominal_starts = std::stoi(given["nominal_starts"]);
  if (part.nominal_starts < 1)
    checker.fail(part.key_lines["nominal_starts"], dotted + ".nominal_starts",
                 dotted + ".nominal_starts = " + given["nominal_starts"] +
                     ": not allowed; allowed: an integer >= 1 (the nominal cases' starts)");
  if (part.points < 1)
    checker.fail(
        part.key_lines["points"], dotted + ".points",
        dotted + ".points = " + given["points"] + ": not allowed; allowed: an integer >= 1 (sample points per case)");
  if (!given.count("series")) part.measurement.series = "none";  // the sample's metrics are its results
}

// A [[validation]] as the study runs it: its suite's settings checked as a suite's, its inputs file read and
// checked, each case a scenario file (a folder: its files), and the first point of every case made once here,
// so that an input the cases cannot take stops the study before anything runs (the inputs file's line named).
ib::StudyPart validation_part(const PartOptions& part) {
  ib::ValidationSettings settings;
  settings.sample = suite_settings_from(part.suite, part.measurement);
  SuiteOptions nominal = part.suite;
  nominal.reference_ensemble_starts = part.nominal_starts;
  settings.nominal = suite_settings_from(nominal, part.measurement);
  SuiteOptions tight = part.suite;
  for (const char* option : {"reference.rtol=1e-12", "reference.atol=1e-15"}) tight.options.push_back(option);
  settings.tight = suite_settings_from(tight, part.measurement);
  settings.inputs = ib::load_uncertain_inputs(part.inputs);
  settings.points = part.points;
  std::vector<std::string> cases;
  for (const std::string& input : settings.sample.inputs) {
    const std::vector<std::string> files =
        fs::is_directory(input) ? ib::find_scenario_files(input) : std::vector<std::string>{input};
    cases.insert(cases.end(), files.begin(), files.end());
  }
  settings.sample.inputs = settings.nominal.inputs = settings.tight.inputs = cases;
  const std::vector<double> first = ib::sobol_input_values(settings.inputs, 1).front();
  for (const std::string& file : cases) {
    ib::load_scenario(file);  // a case's own mistakes named in its own terms first
    ib::scenario_with_inputs(ib::read_text_file(file), file, settings.inputs, first, "check");
  }
  return {ib::StudyPartKind::validation, part.name,
          std::shared_ptr<const ib::PartOfItsOwnKind>(std::make_shared<ib::ValidationPart>(std::move(settings)))};
}

}  // namespace cli
