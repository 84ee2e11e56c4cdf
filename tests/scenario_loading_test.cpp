// Scenario files: the four published cases load with the values of rig.md section 1, and the alternatives the
// schema allows (every kind of mistake: scenario_errors_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "model/scenario_toml.h"
#include "scenario_files.h"

namespace ib {
namespace scenario_loading_test {

using testing::error_from;
using testing::kPaperDir;
using testing::paper_file;
using testing::paper_text_with;
using testing::read_text;

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

}  // namespace scenario_loading_test
}  // namespace ib
