// A rig's uncertain inputs (model/uncertain_inputs.h): the shipped file of the published rig holds together with
// the published scenarios (its nominal values make them again), each distribution's quantiles are the closed
// forms', a sample point moves every key its inputs name, and every mistake in an inputs file is named with its
// file, line, key, value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "model/scenario_toml.h"
#include "model/uncertain_inputs.h"
#include "scenario_files.h"

namespace ib {
namespace uncertain_inputs_test {

const std::string kPaperInputs = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper_inputs.toml";

std::vector<double> nominal_values(const UncertainInputs& inputs) {
  std::vector<double> values;
  for (const UncertainInput& input : inputs.inputs) values.push_back(input.nominal);
  return values;
}

std::size_t index_of(const UncertainInputs& inputs, const std::string& name) {
  for (std::size_t i = 0; i < inputs.inputs.size(); ++i)
    if (inputs.inputs[i].name == name) return i;
  ADD_FAILURE() << "no input " << name;
  return 0;
}

TEST(UncertainInputs, ThePublishedRigsInputsMakeThePublishedScenariosAtTheirNominalValues) {
  const UncertainInputs inputs = load_uncertain_inputs(kPaperInputs);
  ASSERT_GE(inputs.inputs.size(), 10u);
  for (const UncertainInput& input : inputs.inputs) {
    EXPECT_FALSE(input.source.empty()) << input.name;
    EXPECT_GT(input.standard_deviation(), 0) << input.name;
  }
  for (const char* name : {"resonance", "pre_resonance", "post_resonance", "free_vibration"}) {
    const std::string file = testing::paper_file(name);
    const Scenario base = load_scenario(file);
    const Scenario same = parse_scenario(
        scenario_with_inputs(testing::read_text(file), file, inputs, nominal_values(inputs), "same"), "");
    EXPECT_EQ(same.name, "same");
    for (int f = 0; f < 2; ++f) {
      EXPECT_DOUBLE_EQ(same.frames[f].tip_mass_kg, base.frames[f].tip_mass_kg) << name;
      EXPECT_DOUBLE_EQ(same.frames[f].column_thickness_m, base.frames[f].column_thickness_m) << name;
      EXPECT_DOUBLE_EQ(same.frames[f].damping_ratio, base.frames[f].damping_ratio) << name;
    }
    EXPECT_DOUBLE_EQ(same.gap_m, base.gap_m);
    EXPECT_EQ(same.motor.has_value(), base.motor.has_value()) << name;
    if (base.motor) {
      EXPECT_DOUBLE_EQ(*same.motor->speed_ratio_to_f1, *base.motor->speed_ratio_to_f1) << name;
    }
  }
}

// Frame 1's tip mass is its plate, the motor and the unbalance: a point moving the unbalance's mass by 0.05 g moves
// the unbalance and the tip mass alike, and the plate's 10 g the tip mass alone.
TEST(UncertainInputs, APointAddsEachInputsDeviationToEveryKeyItNames) {
  const UncertainInputs inputs = load_uncertain_inputs(kPaperInputs);
  const std::string file = testing::paper_file("resonance");
  const Scenario base = load_scenario(file);
  std::vector<double> values = nominal_values(inputs);
  values[index_of(inputs, "unbalance_mass_kg")] += 0.05e-3;
  values[index_of(inputs, "frame1_plate_mass_kg")] += 0.010;
  values[index_of(inputs, "motor_speed_ratio_offset")] += 0.01;
  const Scenario moved = parse_scenario(scenario_with_inputs(testing::read_text(file), file, inputs, values, "p"), "");
  EXPECT_NEAR(moved.motor->unbalance_mass_kg, base.motor->unbalance_mass_kg + 0.05e-3, 1e-15);
  EXPECT_NEAR(moved.frames[0].tip_mass_kg, base.frames[0].tip_mass_kg + 0.05e-3 + 0.010, 1e-15);
  EXPECT_DOUBLE_EQ(moved.frames[1].tip_mass_kg, base.frames[1].tip_mass_kg);
  EXPECT_NEAR(*moved.motor->speed_ratio_to_f1, 1.01, 1e-15);
  // the nominal plate, motor and unbalance are frame 1's published tip mass
  EXPECT_NEAR(inputs.inputs[index_of(inputs, "frame1_plate_mass_kg")].nominal +
                  inputs.inputs[index_of(inputs, "motor_mass_kg")].nominal +
                  inputs.inputs[index_of(inputs, "unbalance_mass_kg")].nominal,
              base.frames[0].tip_mass_kg, 1e-12);
}

TEST(UncertainInputs, QuantilesAreTheDistributionsClosedForms) {
  UncertainInput uniform;
  uniform.nominal = 2;
  uniform.half_width = 0.5;
  EXPECT_DOUBLE_EQ(uniform.value_at(0), 1.5);
  EXPECT_DOUBLE_EQ(uniform.value_at(1), 2.5);
  EXPECT_DOUBLE_EQ(uniform.value_at(0.5), 2);
  EXPECT_DOUBLE_EQ(uniform.standard_deviation(), 0.5 / std::sqrt(3.0));
  UncertainInput normal;
  normal.distribution = InputDistribution::normal;
  normal.nominal = 10;
  normal.standard_uncertainty = 2;
  EXPECT_DOUBLE_EQ(normal.value_at(0.5), 10);
  EXPECT_NEAR(normal.value_at(0.5 * std::erfc(-1 / std::sqrt(2.0))), 12, 1e-12);  // Phi(1): one deviation up
  EXPECT_NEAR(normal.value_at(0.5 * std::erfc(2 / std::sqrt(2.0))), 6, 1e-12);    // Phi(-2)
}

// ---- Mistakes, each named with the file, the line, the key, the value and what is allowed.

const char* kGood = R"([inputs]
description = "a test"

[[input]]
name = "gap_m"
keys = ["rig.gap_m"]
nominal = 1e-3
distribution = "uniform"
half_width = 1e-4
source = "a test"
)";

// text with line `line` (1-based) replaced by `replacement` ("" removes it).
std::string replace_line(const std::string& text, int line, const std::string& replacement) {
  std::string out, current;
  int number = 1;
  for (char c : text + "\n") {
    if (c != '\n') {
      current += c;
      continue;
    }
    if (number != line)
      out += current + "\n";
    else if (!replacement.empty())
      out += replacement + "\n";
    current.clear();
    ++number;
  }
  return out;
}

struct Mistake {
  int line;
  std::string replacement;
  int message_line;
  std::string key;
  std::vector<std::string> fragments;
};

TEST(UncertainInputs, EveryMistakeIsNamedWithItsLineKeyValueAndWhatIsAllowed) {
  const std::vector<Mistake> mistakes = {
      {8,
       "distribution = \"triangular\"",
       8,
       "input[1].distribution",
       {"\"triangular\"", "allowed: uniform or normal"}},
      {9, "half_width = 0", 9, "input[1].half_width", {"half_width = 0", "> 0"}},
      {9, "", 4, "input[1].half_width", {"missing required key for a uniform input"}},
      {10,
       "standard_uncertainty = 1e-4\nsource = \"a test\"",
       10,
       "input[1].standard_uncertainty",
       {"not allowed for a uniform input"}},
      {6, "keys = []", 6, "input[1].keys", {"keys = []", "non-empty array"}},
      {6, "keys = [\"gap_m\"]", 6, "input[1].keys", {"\"gap_m\"", "dotted"}},
      {5, "name = \"Gap\"", 5, "input[1].name", {"\"Gap\"", "a-z"}},
      {10, "sauce = \"x\"", 10, "input[1].sauce", {"unknown key", "allowed keys in [[input]]"}},
      {2, "", 1, "inputs.description", {"missing required key"}},
  };
  for (const Mistake& m : mistakes) {
    try {
      parse_uncertain_inputs(replace_line(kGood, m.line, m.replacement), "x_inputs.toml");
      ADD_FAILURE() << "no error for line " << m.line << " = " << m.replacement;
    } catch (const ScenarioError& error) {
      EXPECT_EQ(error.path(), "x_inputs.toml");
      EXPECT_EQ(error.line(), m.message_line) << error.what();
      EXPECT_EQ(error.key(), m.key) << error.what();
      for (const std::string& fragment : m.fragments)
        EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << fragment << " in " << error.what();
    }
  }
  // the same name twice: the second one named, with the first's line
  try {
    parse_uncertain_inputs(std::string(kGood) + "\n" + std::string(kGood).substr(std::string(kGood).find("[[input]]")),
                           "x_inputs.toml");
    ADD_FAILURE() << "no error for a name given twice";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(error.line(), 12) << error.what();
    EXPECT_NE(std::string(error.what()).find("already the name of the input at line 4"), std::string::npos)
        << error.what();
  }
}

// A key the scenario's table lacks is a mistake of the inputs file (its line named); a table the scenario lacks
// (the free vibration's motor) leaves that input out of it.
TEST(UncertainInputs, AKeyTheScenarioLacksIsNamedAndATableItLacksIsLeftAlone) {
  const std::string file = testing::paper_file("free_vibration");
  UncertainInputs motor = parse_uncertain_inputs(replace_line(kGood, 6, "keys = [\"motor.unbalance_radius_m\"]"), "m");
  EXPECT_NO_THROW(parse_scenario(scenario_with_inputs(testing::read_text(file), file, motor, {2e-3}, "p"), ""));
  UncertainInputs typo = parse_uncertain_inputs(replace_line(kGood, 6, "keys = [\"rig.gap\"]"), "typo_inputs.toml");
  try {
    scenario_with_inputs(testing::read_text(file), file, typo, {1e-3}, "p");
    ADD_FAILURE() << "no error for rig.gap";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(error.path(), "typo_inputs.toml");
    EXPECT_EQ(error.line(), 4);
    EXPECT_NE(std::string(error.what()).find("rig.gap, which " + file + " does not give"), std::string::npos)
        << error.what();
  }
  // a value the scenario does not allow names the variant
  try {
    scenario_with_inputs(testing::read_text(file), file, parse_uncertain_inputs(kGood, "g"), {-5e-3}, "p7");
    ADD_FAILURE() << "no error for a negative gap";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(error.path(), file + " (p7)") << error.what();
    EXPECT_EQ(error.key(), "rig.gap_m");
  }
}

}  // namespace uncertain_inputs_test
}  // namespace ib
