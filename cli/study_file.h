// A study file (docs/studies.md, "Study files"): a TOML file that lists a study's parts, suites, step
// searches and frequency sweeps, in the same terms as the `suite` and `sweep` commands' options. Reading
// it checks every key's name and type and names the file, the line, the key, the value and what is allowed;
// each part's values are then checked by the very code that checks the commands' options
// (suite_settings_from, sweep_settings_from), so a study and a command line cannot disagree on a range.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace cli {

struct StudyPart {
  enum class Kind { suite, search, sweep };
  Kind kind = Kind::suite;
  std::string name;    // a sweep's: its folder below OUT/sweeps/; a suite's or search's: for messages
  std::string file;    // the study file
  int line = 0;        // its table's header ([[suite]], [[search]], [[sweep]])
  SuiteOptions suite;  // suite and search
  SweepOptions sweep;  // sweep
  MeasurementOptions measurement;
  std::map<std::string, int> key_lines;  // each key given, by its line: messages about a value name it
  std::map<std::string, std::vector<std::string>> key_items;  // an array key's items, as given (a comma in one stays)
};

struct Study {
  std::string file;
  std::string description;
  std::vector<StudyPart> parts;  // in the file's order within each kind: suites, then searches, then sweeps
};

// Reads and checks a study file; throws ib::ScenarioError (file, line, key, message) for an unknown key, a
// wrong type or a value that is not allowed, and for a file that cannot be read. `engines`: this build's
// simulators, what `all` means. Relative scenario paths are taken from the study file's folder, else from
// the project's folder (where scenarios/ is), so that a copy of a study elsewhere still finds the published cases.
Study read_study(const std::string& path, const std::vector<std::string>& engines);

// A part's values checked and turned into its settings as the commands do; an error names the study file,
// the part's key and its line (the key an option's message is about, else the part's header).
ib::SuiteSettings settings_of_suite_part(const StudyPart& part);
ib::SweepSettings settings_of_sweep_part(const StudyPart& part);

}  // namespace cli
