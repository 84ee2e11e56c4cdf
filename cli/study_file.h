// A study file (docs/studies.md, "Study files"): a TOML file that lists a study's parts, suites, step
// searches and frequency sweeps, in the same terms as the `suite` and `sweep` commands' options. Reading
// it checks every key's name and type and names the file, the line, the key, the value and what is allowed;
// each part's values are then checked by the very code that checks the commands' options: the reader turns
// a part's keys into the command's options (SuiteOptions, SweepOptions) and those into its settings with
// suite_settings_from and sweep_settings_from, so a study and a command line cannot disagree on a range (one
// rule per range). What it returns holds typed settings only (harness/study/study.h).
#pragma once

#include <string>
#include <vector>

#include "harness/study/study.h"

namespace cli {

struct Study {
  std::string file;
  std::string description;
  // In the file's order within each kind: suites, then searches, then sweeps; each part's settings checked. The
  // study-wide settings in them (folder, workers, shard, resume, reference cache) are run_study's to set.
  std::vector<ib::StudyPart> parts;
  std::vector<int> lines;  // each part's table header ([[suite]], [[search]], [[sweep]]), for messages
};

// Reads and checks a study file; throws ib::ScenarioError (file, line, key, message) for an unknown key, a
// wrong type or a value that is not allowed, and for a file that cannot be read. `engines`: this build's
// simulators, what `all` means. Relative scenario paths are taken from the study file's folder, else from
// the project's folder (where scenarios/ is), so that a copy of a study elsewhere still finds the published cases.
// The parts of a kind in `left_out` (--skip) have their keys checked by name and type, not their values, and
// are not returned: a study runs as if they were not there.
Study read_study(const std::string& path, const std::vector<std::string>& engines,
                 const std::vector<ib::StudyPartKind>& left_out = {});

}  // namespace cli
