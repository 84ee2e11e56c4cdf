// Every kind of mistake in a scenario file is reported with the file, the line, the key, the value and what is
// allowed: the corpus of malformed files, mistakes in text, and files that cannot be read.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "model/scenario_toml.h"
#include "scenario_files.h"

namespace ib {
namespace scenario_errors_test {

using testing::error_from;
using testing::kMalformedDir;
using testing::kPaperDir;
using testing::malformed_file;
using testing::paper_file;
using testing::paper_text_with;
using testing::read_text;

// ------------------------------------------------------------------------------------------------
// The corpus of malformed scenarios: one file per kind of mistake, in tests/data/malformed_scenarios.

struct MalformedCase {
  std::string file;                    // name without .toml
  int line;                            // where the message points
  std::string key;                     // the dotted key it names
  std::vector<std::string> fragments;  // text the message must contain: value and what is allowed
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.file; }

const std::vector<MalformedCase> kMalformed = {
    {"unknown_key",
     13,
     "frame1.colums",
     {"frame1.colums: unknown key; allowed keys in [frame1]: columns, youngs_modulus_pa, density_kg_m3, "
      "column_thickness_m, column_width_m, length_m, tip_mass_kg, damping_ratio"}},
    {"unknown_table",
     54,
     "output",
     {"output: unknown table; allowed tables: [scenario], [frame1], [frame2], [rig], [motor], [initial], "
      "[contact]"}},
    {"missing_key",
     12,
     "frame1.tip_mass_kg",
     {"frame1.tip_mass_kg: missing required key; allowed: 0 <= x <= 10000 (tip mass [kg])"}},
    {"missing_table", 1, "rig", {"rig: missing required table [rig]"}},
    {"wrong_type_string",
     14,
     "frame1.youngs_modulus_pa",
     {"frame1.youngs_modulus_pa = \"200e9\": wrong type (string); expected a number with 100000 <= x <= 1.5e+12"}},
    {"float_for_integer", 23, "frame2.columns", {"frame2.columns = 2.5: wrong type (float); expected an integer >= 1"}},
    {"out_of_range_columns",
     13,
     "frame1.columns",
     {"frame1.columns = 0: out of range; allowed: >= 1 (number of columns"}},
    {"out_of_range_tip_mass",
     19,
     "frame1.tip_mass_kg",
     {"frame1.tip_mass_kg = -1: out of range; allowed: 0 <= x <= 10000 (tip mass [kg])"}},
    {"out_of_range_damping_ratio",
     30,
     "frame2.damping_ratio",
     {"frame2.damping_ratio = 1.0: out of range; allowed: 0 <= x < 1 (damping ratio"}},
    {"out_of_range_gap", 33, "rig.gap_m", {"rig.gap_m = -1.0e-3: out of range; allowed: 0 <= x <= 0.1 (surface gap"}},
    {"out_of_range_hertz_exponent",
     42,
     "contact.hertz.exponent",
     {"contact.hertz.exponent = 3.5: out of range; allowed: 1 <= x <= 3 (Hertz exponent n [-])"}},
    {"out_of_range_newton_restitution",
     52,
     "contact.newton.restitution",
     {"contact.newton.restitution = 1.2: out of range; allowed: 0 <= x <= 1 (coefficient of restitution"}},
    {"out_of_range_initial_displacement",
     37,
     "initial.frame1_tip_displacement_m",
     {"initial.frame1_tip_displacement_m = -0.05: out of range; allowed: |x| <= frame1.length_m / 10 = 0.03",
      "small-deflection theory"}},
    {"motor_both_speeds",
     39,
     "motor.frequency_hz",
     {"motor.frequency_hz = 6.95: conflicts with motor.speed_ratio_to_f1 = 1.00 (line 38)",
      "allowed: exactly one of motor.speed_ratio_to_f1 0 < x <= 100", "or motor.frequency_hz 0 < x <= 10000"}},
    {"motor_no_speed",
     35,
     "motor",
     {"motor: the motor speed is missing", "allowed: exactly one of motor.speed_ratio_to_f1 0 < x <= 100",
      "or motor.frequency_hz 0 < x <= 10000"}},
    {"hertz_damping_and_restitution",
     45,
     "contact.hertz.damping",
     {"contact.hertz.damping = 1.01e11: ambiguous together with contact.hertz.restitution = 0.8 (line 43)",
      "allowed: either contact.hertz.damping"}},
    {"hertz_missing_approach_velocity",
     40,
     "contact.hertz.approach_velocity_m_s",
     {"contact.hertz.approach_velocity_m_s: missing required key; allowed: 0 < x <= 100 (mean approach velocity",
      "only when contact.hertz.damping is given"}},
    {"syntax_error", 18, "", {"TOML syntax error: "}},
    {"non_finite_nan",
     24,
     "frame2.youngs_modulus_pa",
     {"frame2.youngs_modulus_pa = nan: not a finite number; allowed: 100000 <= x <= 1.5e+12 (Young's modulus E [Pa]"}},
    {"non_finite_inf",
     41,
     "contact.hertz.stiffness",
     {"contact.hertz.stiffness = inf: not a finite number; allowed: 0 < x <= 1e+15 (Hertz stiffness k_h [N/m^n])"}},
    {"empty_name",
     6,
     "scenario.name",
     {"scenario.name = \"\": not a valid name; allowed: 1 to 64 characters of a-z, 0-9 and _"}},
    {"window_longer_than_duration",
     9,
     "scenario.scoring_window_s",
     {"scenario.scoring_window_s = 150.0: out of range; allowed: 0 < x <= scenario.duration_s = 100"}},
    // plausibility (issue 20): each value within its type, none within physics
    {"out_of_range_youngs_modulus",
     14,
     "frame1.youngs_modulus_pa",
     {"frame1.youngs_modulus_pa = 1e300: out of range; allowed: 100000 <= x <= 1.5e+12"}},
    {"not_slender_column",
     16,
     "frame1.column_thickness_m",
     {"frame1.column_thickness_m = 1.0: out of range; allowed: x <= frame1.length_m / 10 = 0.03", "slender column"}},
    {"frequency_too_low",
     12,
     "frame1",
     {"frame1: its first natural frequency would be about 0.0049", "frame1.youngs_modulus_pa = 100000",
      "allowed: 0.05 to 5000 Hz"}},
    {"name_too_long", 6, "scenario.name", {"not a valid name; allowed: 1 to 64 characters of a-z, 0-9 and _"}},
    {"duration_too_long",
     8,
     "scenario.duration_s",
     {"scenario.duration_s = 1e300: out of range; allowed: 0 < x <= 3600"}},
    {"boolean_as_string",
     49,
     "contact.viscoelastic.clip_tension",
     {"contact.viscoelastic.clip_tension = \"no\": wrong type (string); expected a boolean (true or false)"}},
};

class MalformedScenario : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedScenario, IsReportedWithFileLineKeyValueAndWhatIsAllowed) {
  const MalformedCase& c = GetParam();
  const std::string path = malformed_file(c.file);
  const ScenarioError error = error_from([&] { load_scenario(path); });
  const std::string what = error.what();

  EXPECT_EQ(error.path(), path);
  EXPECT_EQ(error.line(), c.line) << what;
  EXPECT_EQ(error.key(), c.key) << what;
  const std::string location = path + ":" + std::to_string(c.line) + ":";
  EXPECT_EQ(what.rfind(location, 0), 0u) << "message does not begin with " << location << "\n" << what;
  for (const std::string& fragment : c.fragments) {
    EXPECT_NE(what.find(fragment), std::string::npos) << "missing \"" << fragment << "\" in\n" << what;
  }
  if (!c.key.empty()) {  // the message begins "<path>:<line>: <key>"
    EXPECT_EQ(what.rfind(location + " " + c.key, 0), 0u) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedScenario, ::testing::ValuesIn(kMalformed),
                         [](const auto& info) { return info.param.file; });

TEST(MalformedCorpus, EveryFileHasACase) {
  std::vector<std::string> listed;
  for (const MalformedCase& c : kMalformed) listed.push_back(malformed_file(c.file));
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(find_scenario_files(kMalformedDir), listed);
}

TEST(MalformedSyntax, GivesLineAndColumn) {
  const std::string path = malformed_file("syntax_error");
  const ScenarioError error = error_from([&] { load_scenario(path); });
  EXPECT_EQ(error.line(), 18);
  EXPECT_GT(error.column(), 0);
  EXPECT_EQ(
      std::string(error.what()).rfind(path + ":18:" + std::to_string(error.column()) + ": TOML syntax error: ", 0), 0u)
      << error.what();
}

// Mistakes checked on text rather than files: the same messages from parse_scenario.
TEST(MalformedText, NoContactLaw) {
  std::istringstream in(read_text(paper_file("free_vibration")));
  std::string line, out;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n >= 39) break;
    out += line + "\n";
  }
  out += "[contact]\n";  // line 39
  const ScenarioError error = error_from([&] { parse_scenario(out, "x.toml"); });
  EXPECT_EQ(error.line(), 39);
  EXPECT_EQ(error.key(), "contact");
  EXPECT_NE(std::string(error.what())
                .find("x.toml:39: contact: no contact law given; allowed: at least one "
                      "of the tables [contact.hertz], [contact.viscoelastic], "
                      "[contact.newton]"),
            std::string::npos)
      << error.what();
}

TEST(MalformedText, TableWhereABooleanIsExpected) {
  const std::string text = paper_text_with("resonance", 49, "clip_tension = { on = true }");
  const ScenarioError error = error_from([&] { parse_scenario(text, "x.toml"); });
  EXPECT_EQ(error.key(), "contact.viscoelastic.clip_tension");
  EXPECT_NE(std::string(error.what())
                .find("x.toml:49: contact.viscoelastic.clip_tension: wrong type (table); expected a boolean"),
            std::string::npos)
      << error.what();
}

TEST(MalformedText, UnknownContactLaw) {
  const std::string text = paper_text_with("resonance", 50, "[contact.hooke]");
  const ScenarioError error = error_from([&] { parse_scenario(text, "x.toml"); });
  EXPECT_EQ(error.key(), "contact.hooke");
  EXPECT_NE(std::string(error.what())
                .find("x.toml:50: contact.hooke: unknown table; allowed tables in [contact]: [contact.hertz], "
                      "[contact.viscoelastic], [contact.newton]"),
            std::string::npos)
      << error.what();
}

TEST(MalformedText, NameWithCapitals) {
  const std::string text = paper_text_with("resonance", 6, "name = \"Resonance 2\"");
  const ScenarioError error = error_from([&] { parse_scenario(text, "x.toml"); });
  EXPECT_NE(std::string(error.what()).find("x.toml:6: scenario.name = \"Resonance 2\": not a valid name"),
            std::string::npos)
      << error.what();
}

TEST(MalformedText, EmptyDocumentMissesTheScenarioTable) {
  const ScenarioError error = error_from([&] { parse_scenario("# nothing here\n", "x.toml"); });
  EXPECT_EQ(error.line(), 1);
  EXPECT_EQ(error.key(), "scenario");
  EXPECT_NE(std::string(error.what()).find("x.toml:1: scenario: missing required table [scenario]"), std::string::npos)
      << error.what();
}

// ------------------------------------------------------------------------------------------------
// Files that cannot be read.

TEST(UnreadableScenario, MissingFileNamesThePath) {
  const std::string path = kMalformedDir + "/no_such_scenario.toml";
  const ScenarioError error = error_from([&] { load_scenario(path); });
  EXPECT_EQ(error.path(), path);
  EXPECT_EQ(error.line(), 0);
  EXPECT_EQ(std::string(error.what()), path + ": cannot read scenario file: No such file or directory");
}

TEST(UnreadableScenario, FolderNamesThePath) {
  const ScenarioError error = error_from([&] { load_scenario(kPaperDir); });
  EXPECT_EQ(std::string(error.what()).rfind(kPaperDir + ": cannot read scenario file: ", 0), 0u) << error.what();
}

}  // namespace scenario_errors_test
}  // namespace ib
