// Scenario files: the four published cases load with the values of rig.md section 1, and every kind of
// mistake in a scenario file is reported with the file, the line, the key, the value and what is allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "model/scenario_toml.h"

namespace ib {
namespace scenario_loading_test {

const std::string kPaperDir = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper";
const std::string kMalformedDir = std::string(IMPACTBENCH_TEST_DATA_DIR) + "/malformed_scenarios";

std::string paper_file(const std::string& name) { return kPaperDir + "/" + name + ".toml"; }
std::string malformed_file(const std::string& name) { return kMalformedDir + "/" + name + ".toml"; }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The text of a paper file with line `line` (1-based) replaced by `replacement` (which may hold
// several lines, or be empty to leave a blank line).
std::string paper_text_with(const std::string& name, int line, const std::string& replacement) {
  std::istringstream in(read_text(paper_file(name)));
  std::string out, current;
  for (int n = 1; std::getline(in, current); ++n) out += (n == line ? replacement : current) + "\n";
  return out;
}

// The ScenarioError thrown by `load`, or a failed test if none is thrown.
template <class Load>
ScenarioError error_from(Load load) {
  try {
    load();
  } catch (const ScenarioError& error) {
    return error;
  }
  ADD_FAILURE() << "no ScenarioError thrown";
  return ScenarioError("", 0, "", "");
}

#define EXPECT_REL_NEAR(actual, expected, rel) EXPECT_NEAR((actual), (expected), std::abs(expected) * (rel))

// ------------------------------------------------------------------------------------------------
// The four published cases (rig.md sections 1 and 7).

struct PaperCase {
  std::string name;
  bool forced;           // motor present
  double speed_ratio;    // motor speed / f_1
  double initial_tip_m;  // frame 1's initial tip displacement
  double duration_s;
  double window_s;
};

void PrintTo(const PaperCase& c, std::ostream* os) { *os << c.name; }

class PaperScenario : public ::testing::TestWithParam<PaperCase> {};

TEST_P(PaperScenario, LoadsWithTheValuesOfRigSection1) {
  const PaperCase& c = GetParam();
  const std::string path = paper_file(c.name);
  const Scenario s = load_scenario(path);

  EXPECT_EQ(s.name, c.name);
  EXPECT_FALSE(s.description.empty());
  EXPECT_EQ(s.source_path, path);
  EXPECT_DOUBLE_EQ(s.duration_s, c.duration_s);
  EXPECT_DOUBLE_EQ(s.scoring_window_s, c.window_s);

  for (const FrameSpec& frame : s.frames) {
    EXPECT_EQ(frame.columns, 2);
    EXPECT_REL_NEAR(frame.bending_stiffness_n_m2(), 13.612, 1e-3);  // EI = 2 E b h^3 / 12
    EXPECT_REL_NEAR(frame.mass_per_length_kg_m(), 2.0936, 1e-4);    // rho A = 2 rho b h
    EXPECT_DOUBLE_EQ(frame.length_m, 0.300);
    EXPECT_DOUBLE_EQ(frame.damping_ratio, 0.003);
  }
  EXPECT_DOUBLE_EQ(s.frames[0].tip_mass_kg, 0.64439);  // plate + motor + unbalance
  EXPECT_DOUBLE_EQ(s.frames[1].tip_mass_kg, 0.41380);  // plate
  EXPECT_DOUBLE_EQ(s.gap_m, 1e-3);

  ASSERT_EQ(s.motor.has_value(), c.forced);
  if (c.forced) {
    EXPECT_DOUBLE_EQ(s.motor->unbalance_mass_kg, 6.59e-3);
    EXPECT_DOUBLE_EQ(s.motor->unbalance_radius_m, 15e-3);
    ASSERT_TRUE(s.motor->speed_ratio_to_f1.has_value());
    EXPECT_DOUBLE_EQ(*s.motor->speed_ratio_to_f1, c.speed_ratio);
    EXPECT_FALSE(s.motor->frequency_hz.has_value());
  }
  EXPECT_DOUBLE_EQ(s.initial.frame1_tip_displacement_m, c.initial_tip_m);

  ASSERT_TRUE(s.contact.has(ContactLaw::hertz));
  ASSERT_TRUE(s.contact.has(ContactLaw::viscoelastic));
  ASSERT_TRUE(s.contact.has(ContactLaw::newton));
  EXPECT_DOUBLE_EQ(s.contact.hertz->stiffness, 2.31e10);
  EXPECT_DOUBLE_EQ(s.contact.hertz->exponent, 1.5);
  EXPECT_FALSE(s.contact.hertz->damping.has_value());
  EXPECT_REL_NEAR(s.contact.hertz->damping_coefficient(), 3.794e10, 1e-3);  // rig.md 6.4
  EXPECT_DOUBLE_EQ(s.contact.viscoelastic->stiffness_n_per_m, 6.99e6);
  EXPECT_DOUBLE_EQ(s.contact.viscoelastic->damping_n_s_per_m, 170.07);
  EXPECT_FALSE(s.contact.viscoelastic->clip_tension);
  EXPECT_DOUBLE_EQ(s.contact.newton->restitution, 0.8);
}

INSTANTIATE_TEST_SUITE_P(Paper, PaperScenario,
                         ::testing::Values(PaperCase{"resonance", true, 1.00, 0.0, 100, 14},
                                           PaperCase{"post_resonance", true, 1.17, 0.0, 100, 14},
                                           PaperCase{"pre_resonance", true, 0.95, 0.0, 100, 14},
                                           PaperCase{"free_vibration", false, 0.0, -2e-3, 14, 14}),
                         [](const auto& info) { return info.param.name; });

TEST(DefaultRig, EqualsTheResonanceFile) {
  const Scenario file = load_scenario(paper_file("resonance"));
  const Scenario rig = default_rig();
  EXPECT_EQ(rig.name, file.name);
  EXPECT_EQ(rig.description, file.description);
  EXPECT_EQ(rig.source_path, "");
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(rig.frames[f].columns, file.frames[f].columns);
    EXPECT_DOUBLE_EQ(rig.frames[f].youngs_modulus_pa, file.frames[f].youngs_modulus_pa);
    EXPECT_DOUBLE_EQ(rig.frames[f].density_kg_m3, file.frames[f].density_kg_m3);
    EXPECT_DOUBLE_EQ(rig.frames[f].column_thickness_m, file.frames[f].column_thickness_m);
    EXPECT_DOUBLE_EQ(rig.frames[f].column_width_m, file.frames[f].column_width_m);
    EXPECT_DOUBLE_EQ(rig.frames[f].length_m, file.frames[f].length_m);
    EXPECT_DOUBLE_EQ(rig.frames[f].tip_mass_kg, file.frames[f].tip_mass_kg);
    EXPECT_DOUBLE_EQ(rig.frames[f].damping_ratio, file.frames[f].damping_ratio);
  }
  EXPECT_DOUBLE_EQ(rig.gap_m, file.gap_m);
  ASSERT_TRUE(rig.motor.has_value());
  EXPECT_DOUBLE_EQ(rig.motor->unbalance_mass_kg, file.motor->unbalance_mass_kg);
  EXPECT_DOUBLE_EQ(rig.motor->unbalance_radius_m, file.motor->unbalance_radius_m);
  EXPECT_EQ(rig.motor->speed_ratio_to_f1, file.motor->speed_ratio_to_f1);
  EXPECT_EQ(rig.motor->frequency_hz, file.motor->frequency_hz);
  EXPECT_DOUBLE_EQ(rig.initial.frame1_tip_displacement_m, file.initial.frame1_tip_displacement_m);
  ASSERT_TRUE(rig.contact.hertz && rig.contact.viscoelastic && rig.contact.newton);
  EXPECT_DOUBLE_EQ(rig.contact.hertz->stiffness, file.contact.hertz->stiffness);
  EXPECT_DOUBLE_EQ(rig.contact.hertz->exponent, file.contact.hertz->exponent);
  EXPECT_DOUBLE_EQ(rig.contact.hertz->restitution, file.contact.hertz->restitution);
  EXPECT_DOUBLE_EQ(rig.contact.hertz->approach_velocity_m_s, file.contact.hertz->approach_velocity_m_s);
  EXPECT_EQ(rig.contact.hertz->damping, file.contact.hertz->damping);
  EXPECT_DOUBLE_EQ(rig.contact.viscoelastic->stiffness_n_per_m, file.contact.viscoelastic->stiffness_n_per_m);
  EXPECT_DOUBLE_EQ(rig.contact.viscoelastic->damping_n_s_per_m, file.contact.viscoelastic->damping_n_s_per_m);
  EXPECT_EQ(rig.contact.viscoelastic->clip_tension, file.contact.viscoelastic->clip_tension);
  EXPECT_DOUBLE_EQ(rig.contact.newton->restitution, file.contact.newton->restitution);
  EXPECT_DOUBLE_EQ(rig.duration_s, file.duration_s);
  EXPECT_DOUBLE_EQ(rig.scoring_window_s, file.scoring_window_s);
  EXPECT_DOUBLE_EQ(scoring_window(rig).start_s, 86.0);
}

TEST(ContactLawNames, RoundTrip) {
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
    EXPECT_EQ(contact_law_from_string(to_string(law)), law);
  }
  EXPECT_STREQ(to_string(ContactLaw::hertz), "hertz");
  EXPECT_STREQ(to_string(ContactLaw::viscoelastic), "viscoelastic");
  EXPECT_STREQ(to_string(ContactLaw::newton), "newton");
  EXPECT_FALSE(contact_law_from_string("Hertz").has_value());
  EXPECT_FALSE(contact_law_from_string("").has_value());
}

TEST(ScenarioFiles, FindsThePaperFilesSorted) {
  const std::vector<std::string> expected = {paper_file("free_vibration"), paper_file("post_resonance"),
                                             paper_file("pre_resonance"), paper_file("resonance")};
  EXPECT_EQ(find_scenario_files(kPaperDir), expected);
}

TEST(ScenarioFiles, MissingFolderIsAnError) {
  const std::string folder = kPaperDir + "/no_such_folder";
  const ScenarioError error = error_from([&] { find_scenario_files(folder); });
  EXPECT_EQ(error.path(), folder);
  EXPECT_NE(std::string(error.what()).find(folder + ": cannot read scenario folder"), std::string::npos)
      << error.what();
}

// ------------------------------------------------------------------------------------------------
// The alternatives the schema allows.

TEST(ScenarioAlternatives, MotorSpeedInHertz) {
  const Scenario s = parse_scenario(paper_text_with("resonance", 38, "frequency_hz = 7"), "in-memory.toml");
  ASSERT_TRUE(s.motor.has_value());
  EXPECT_FALSE(s.motor->speed_ratio_to_f1.has_value());
  EXPECT_EQ(s.motor->frequency_hz, 7.0);  // an integer where a number is expected
  EXPECT_EQ(s.source_path, "in-memory.toml");
}

TEST(ScenarioAlternatives, ExplicitHertzDamping) {
  // Restitution and approach velocity (lines 43-44) replaced by an explicit c_h.
  std::istringstream in(read_text(paper_file("resonance")));
  std::string line, out;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n == 43) out += "damping = 1.01e11\n";
    if (n == 43 || n == 44) continue;
    out += line + "\n";
  }
  const Scenario s = parse_scenario(out, "in-memory.toml");
  ASSERT_TRUE(s.contact.hertz.has_value());
  EXPECT_EQ(s.contact.hertz->damping, 1.01e11);
  EXPECT_DOUBLE_EQ(s.contact.hertz->damping_coefficient(), 1.01e11);
}

TEST(ScenarioAlternatives, OneContactLawIsEnough) {
  std::istringstream in(read_text(paper_file("free_vibration")));
  std::string line, out;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n >= 39 && n <= 49) continue;  // keep only [contact.newton]
    out += line + "\n";
  }
  const Scenario s = parse_scenario(out, "in-memory.toml");
  EXPECT_FALSE(s.contact.has(ContactLaw::hertz));
  EXPECT_FALSE(s.contact.has(ContactLaw::viscoelastic));
  EXPECT_TRUE(s.contact.has(ContactLaw::newton));
  EXPECT_FALSE(s.motor.has_value());
}

TEST(ScenarioAlternatives, ClipTensionDefaultsToFalse) {
  const Scenario s = parse_scenario(paper_text_with("resonance", 49, ""), "in-memory.toml");
  EXPECT_FALSE(s.contact.viscoelastic->clip_tension);
  const Scenario clipped = parse_scenario(paper_text_with("resonance", 49, "clip_tension = true"), "x.toml");
  EXPECT_TRUE(clipped.contact.viscoelastic->clip_tension);
}

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

}  // namespace scenario_loading_test
}  // namespace ib
