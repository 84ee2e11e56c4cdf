// A rig's inputs with their uncertainty (an *_inputs.toml file, scenarios/paper_inputs.toml; docs/validation.md):
// each input a physical quantity with its nominal value, its distribution and the scenario keys it moves, so
// that a validation can draw a sample of the published scenarios. Reading checks every key as a scenario file's
// are checked, and a bad file stops with a ScenarioError naming the file, the line, the key, the value and what
// is allowed.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace ib {

enum class InputDistribution { uniform, normal };

struct UncertainInput {
  std::string name;               // what it is, its unit last ("gap_m"): the sample's column
  std::vector<std::string> keys;  // the scenario keys it moves, dotted ("frame1.column_thickness_m")
  double nominal = 0;
  InputDistribution distribution = InputDistribution::uniform;
  double half_width = 0;            // uniform: nominal +- half_width
  double standard_uncertainty = 0;  // normal: one standard deviation
  std::string source;               // where the nominal value and the spread come from
  int line = 0;                     // its [[input]] header in the file

  double standard_deviation() const;  // uniform: half_width / sqrt(3)
  // The value at probability u of its distribution, 0 < u < 1 (a uniform's ends are included).
  double value_at(double u) const;
};

struct UncertainInputs {
  std::string path;
  std::string description;
  std::vector<UncertainInput> inputs;  // in the file's order
};

UncertainInputs load_uncertain_inputs(const std::string& path);
UncertainInputs parse_uncertain_inputs(std::string_view toml_text, const std::string& path);

// The scenario text `base_text` (read from base_path) with each input's deviation from its nominal
// (values[i] - inputs[i].nominal) added to every key it names and the scenario's name set to `name`; a key whose
// table the scenario has not (a motor's key in the free vibration) is not moved. Throws a ScenarioError naming the
// inputs file and the input's line for a key the scenario's table lacks or that is not a number there, and naming
// the variant as base_path + " (name)" for a value the scenario does not allow.
std::string scenario_with_inputs(const std::string& base_text, const std::string& base_path,
                                 const UncertainInputs& inputs, const std::vector<double>& values,
                                 const std::string& name);

}  // namespace ib
