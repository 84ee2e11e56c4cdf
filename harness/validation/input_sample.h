// A validation's sample of a rig's uncertain inputs (docs/validation.md): the points of a Sobol' sequence
// (Boost.Random's, deterministic, so a resumed study draws the very same sample) mapped through each input's
// distribution, and each published case's scenario file rewritten at every point.
#pragma once

#include <string>
#include <vector>

#include "model/uncertain_inputs.h"

namespace ib {

// values[p][i]: input i at point p. Point 0 is the sequence's centre (Boost's sequence leaves out the corner 0,
// where a normal input has no value): every input at its median, the nominal rig.
std::vector<std::vector<double>> sobol_input_values(const UncertainInputs& inputs, int points);

// What write_input_sample wrote: every case's scenario file at every point, case by case.
struct InputSampleFiles {
  std::vector<std::string> scenario_files;
};

// Writes FOLDER/scenarios/CASE/CASE_pNNN.toml for each case file (a scenario with its [scenario] name CASE) and
// point, FOLDER/sample.csv (case, point, scenario, scenario_file, then each input's value, its name the column)
// and FOLDER/inputs.json (the inputs with their sources, the design and the points). Throws ScenarioError for a
// case the inputs cannot move (scenario_with_inputs) and OutputError (run_files.h) for a file it cannot write.
InputSampleFiles write_input_sample(const UncertainInputs& inputs, const std::vector<std::string>& case_files,
                                    int points, const std::string& folder);

}  // namespace ib
