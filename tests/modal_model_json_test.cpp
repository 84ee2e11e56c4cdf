// The modal model as JSON (reference/modal_model_json.h, `impactbench export --engine reference`): every
// exported number equals the model's bit for bit after reading it back, the recorded levers give the
// reference's own tip displacement, only the chosen law is written and "motor" only with a motor.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reference/modal_model_json.h"
#include "reference_fixtures.h"

namespace ib {
namespace modal_model_json_test {

using Json = nlohmann::json;

ModelRunInfo run_info(const Scenario& s) {
  ModelRunInfo run;
  run.scenario_name = s.name;
  run.scenario_file = s.source_path;
  run.duration_s = s.duration_s;
  run.scoring_window = scoring_window(s);
  run.series_start_s = run.scoring_window.start_s;
  run.output_rate_hz = 4096;
  return run;
}

Json exported(const Scenario& s, ContactLaw law, const ReferenceSettings& settings = {}) {
  const ModalModel model = build_modal_model(s, law, settings.modes);
  return Json::parse(modal_model_json(model, initial_state(s, model), run_info(s), settings));
}

void expect_equal(const Json& array, const Eigen::VectorXd& values, const std::string& key) {
  ASSERT_EQ(array.size(), static_cast<std::size_t>(values.size())) << key;
  for (int i = 0; i < values.size(); ++i) EXPECT_EQ(array[i].get<double>(), values[i]) << key << "[" << i << "]";
}

TEST(ModalModelJson, NumbersEqualTheModels) {
  const Scenario s = testing::paper_scenario("resonance");
  ReferenceSettings settings;
  settings.modes.modes_per_frame = 7;
  settings.relative_tolerance = 3e-10;
  settings.absolute_tolerance = 2e-13;
  const ModalModel model = build_modal_model(s, ContactLaw::hertz, settings.modes);
  const ModalState initial = initial_state(s, model);
  const Json j = Json::parse(modal_model_json(model, initial, run_info(s), settings));
  expect_equal(j["omega_rad_s"], model.omega_rad_s, "omega_rad_s");
  expect_equal(j["zeta"], model.zeta, "zeta");
  expect_equal(j["contact_lever_per_sqrt_kg"], model.contact_lever, "contact_lever_per_sqrt_kg");
  expect_equal(j["motor_lever_per_sqrt_kg"], model.motor_lever, "motor_lever_per_sqrt_kg");
  expect_equal(j["initial"]["q_m_sqrt_kg"], initial.q, "q");
  expect_equal(j["initial"]["v_m_s_sqrt_kg"], initial.v, "v");
  EXPECT_EQ(j["frame_mode_counts"], Json::array({7, 7}));
  EXPECT_EQ(j["gap_m"].get<double>(), model.gap_m);
  EXPECT_EQ(j["motor"]["amplitude_n"].get<double>(), model.motor->amplitude_n);
  EXPECT_EQ(j["motor"]["omega_rad_s"].get<double>(), model.motor->omega_rad_s);
  const HertzLaw& hertz = std::get<HertzLaw>(model.contact);
  EXPECT_EQ(j["contact_law"]["name"], "hertz");
  EXPECT_EQ(j["contact_law"]["stiffness_n_per_m_pow_n"].get<double>(), hertz.stiffness);
  EXPECT_EQ(j["contact_law"]["exponent"].get<double>(), hertz.exponent);
  EXPECT_EQ(j["contact_law"]["damping_n_s_per_m_pow_n_plus_1"].get<double>(), hertz.damping);
  EXPECT_EQ(j["duration_s"].get<double>(), s.duration_s);
  EXPECT_EQ(j["series_start_s"].get<double>(), scoring_window(s).start_s);
  EXPECT_EQ(j["scoring_window_start_s"].get<double>(), scoring_window(s).start_s);
  EXPECT_EQ(j["scoring_window_end_s"].get<double>(), s.duration_s);
  EXPECT_EQ(j["output_rate_hz"].get<double>(), 4096);
  EXPECT_EQ(j["reference_settings"]["rtol"].get<double>(), 3e-10);
  EXPECT_EQ(j["reference_settings"]["atol_m_sqrt_kg"].get<double>(), 2e-13);
  EXPECT_EQ(j["reference_settings"]["accumulation_time_s"].get<double>(), settings.accumulation_time_s);
}

// lever_f . q is the tip displacement the reference records at t = 0 (frame 1 starts deflected 2 mm).
TEST(ModalModelJson, TipLeversGiveTheRecordedDisplacement) {
  const Scenario s = testing::paper_scenario("free_vibration");
  const ModalModel model = build_modal_model(s, ContactLaw::viscoelastic, {});
  const ModalState initial = initial_state(s, model);
  const Json j = Json::parse(modal_model_json(model, initial, run_info(s), {}));
  const ReferenceSolution solution = testing::solve(model, initial, 1e-3);
  for (int f = 0; f < 2; ++f) {
    const Json& lever = j["recorded"]["frame" + std::to_string(f + 1) + "_tip_lever_per_sqrt_kg"];
    double u = 0;
    for (int m = 0; m < model.mode_count(); ++m) u += lever[m].get<double>() * initial.q[m];
    EXPECT_NEAR(u, solution.trajectory.displacement_m[f][0], 1e-15) << "frame " << f + 1;
  }
  EXPECT_NEAR(solution.trajectory.displacement_m[0][0], -2e-3, 1e-12);
}

TEST(ModalModelJson, OnlyTheChosenLawAndMotorOnlyWithOne) {
  const Scenario free = testing::paper_scenario("free_vibration");
  const Json viscoelastic = exported(free, ContactLaw::viscoelastic)["contact_law"];
  EXPECT_EQ(viscoelastic["name"], "viscoelastic");
  EXPECT_EQ(viscoelastic["stiffness_n_per_m"].get<double>(), free.contact.viscoelastic->stiffness_n_per_m);
  EXPECT_EQ(viscoelastic["damping_n_s_per_m"].get<double>(), free.contact.viscoelastic->damping_n_s_per_m);
  EXPECT_EQ(viscoelastic["clip_tension"].get<bool>(), free.contact.viscoelastic->clip_tension);
  EXPECT_FALSE(viscoelastic.contains("restitution"));
  const Json newton = exported(free, ContactLaw::newton);
  EXPECT_EQ(newton["contact_law"]["restitution"].get<double>(), free.contact.newton->restitution);
  EXPECT_FALSE(newton["contact_law"].contains("stiffness_n_per_m"));
  EXPECT_FALSE(newton.contains("motor"));  // free vibration: no motor at all
  EXPECT_TRUE(exported(testing::paper_scenario("resonance"), ContactLaw::newton).contains("motor"));
}

}  // namespace modal_model_json_test
}  // namespace ib
