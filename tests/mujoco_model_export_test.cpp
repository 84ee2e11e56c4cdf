// The MJCF a run builds (mujoco_model_xml, what `impactbench export --engine mujoco` writes) loads with
// mj_loadXML from a file and is the rig: body masses, centres of mass and inertias, hinge stiffness and
// damping, the tip spheres' gap, the initial angles, the time step and integrator, and for each
// contact path only the contact it needs. Bad options are rejected before anything runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "adapters/common/rig.h"
#include "adapters/mujoco/mujoco_engine.h"
#include "adapters/mujoco/mujoco_model.h"
#include "adapters/mujoco/mujoco_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace mujoco_model_export_test {

namespace fs = std::filesystem;

// Writes the text to a file of its own, loads it the way a person would (mj_loadXML from a path), and
// removes the file.
MujocoModelPtr load_from_file(const std::string& xml) {
  install_mujoco_handlers();
  const fs::path file =
      fs::temp_directory_path() / ("impactbench_mujoco_export_" + std::to_string(::getpid()) + ".xml");
  std::ofstream(file) << xml;
  char error[1024] = "";
  MujocoModelPtr model(mj_loadXML(file.c_str(), nullptr, error, sizeof error));
  fs::remove(file);
  EXPECT_TRUE(model) << error;
  return model;
}

RunSettings settings(ContactLaw law, const std::string& contact) {
  RunSettings s;
  s.law = law;
  s.time_step_s = 5e-5;
  s.options = {{"contact", contact}};
  return s;
}

int id(const mjModel* m, mjtObj type, const std::string& name) {
  const int i = mj_name2id(m, type, name.c_str());
  EXPECT_GE(i, 0) << name;
  return i;
}

// Every body, joint and the tip geometry against the rig the run is built from.
void expect_rig(const mjModel* m, const RigSpec& rig, int links) {
  ASSERT_EQ(m->nbody, 1 + 2 * links);  // the world and two chains
  ASSERT_EQ(m->njnt, 2 * links);
  EXPECT_EQ(m->opt.gravity[2], 0);
  for (int f = 0; f < 2; ++f) {
    const FrameRig& frame = rig.frames[f];
    for (int j = 0; j < links; ++j) {
      const RigBody& body = frame.bodies[j];
      const int b = id(m, mjOBJ_BODY, mujoco_body_name(f, j));
      EXPECT_NEAR(m->body_mass[b], body.mass_kg, 1e-14) << "frame " << f + 1 << " body " << j + 1;
      EXPECT_NEAR(m->body_ipos[3 * b + 2], body.com_z_m - body.joint_z_m, 1e-14);
      EXPECT_NEAR(m->body_inertia[3 * b + 1], body.inertia_y_kg_m2, 1e-18);  // about the hinge axis y
      const int joint = id(m, mjOBJ_JOINT, mujoco_joint_name(f, j));
      EXPECT_EQ(m->jnt_type[joint], mjJNT_HINGE);
      EXPECT_EQ(m->jnt_axis[3 * joint + 1], 1);
      EXPECT_NEAR(m->jnt_stiffness[joint], frame.chain.joint_stiffness_n_m_per_rad[j], 1e-12);
      EXPECT_NEAR(m->dof_damping[m->jnt_dofadr[joint]], frame.chain.joint_damping_n_m_s_per_rad[j], 1e-15);
    }
  }
  // at the straight rest state the tip spheres' surfaces are the gap apart, at the tips
  MujocoDataPtr data = make_data(m);
  mj_kinematics(m, data.get());
  const int g1 = id(m, mjOBJ_GEOM, mujoco_tip_geom_name(0)), g2 = id(m, mjOBJ_GEOM, mujoco_tip_geom_name(1));
  const double* p1 = data->geom_xpos + 3 * g1;
  const double* p2 = data->geom_xpos + 3 * g2;
  EXPECT_NEAR(p2[0] - p1[0] - m->geom_size[3 * g1] - m->geom_size[3 * g2], rig.gap_m, 1e-15);
  EXPECT_NEAR(p1[2], rig.frames[0].tip_z_m, 1e-15);
  const int site = id(m, mjOBJ_SITE, mujoco_tip_site_name(1));
  EXPECT_NEAR(data->site_xpos[3 * site], rig.frame_spacing_m, 1e-15);
}

TEST(MujocoModelExport, LoadsFromAFileAndIsTheRig) {
  Scenario s = testing::paper_scenario("free_vibration");
  const RunSettings run = settings(ContactLaw::viscoelastic, "matched");
  const std::string xml = mujoco_model_xml(s, run);
  EXPECT_NE(xml.find("<compiler angle=\"radian\""), std::string::npos);
  MujocoModelPtr model = load_from_file(xml);
  ASSERT_TRUE(model);
  const int links = default_links(s);
  const RigSpec rig = build_rig(s, ContactLaw::viscoelastic, links);
  expect_rig(model.get(), rig, links);
  EXPECT_EQ(model->opt.timestep, 5e-5);
  EXPECT_EQ(model->opt.integrator, mjINT_EULER);
  // the release state: frame 1's static tip-load angles, frame 2 straight
  ASSERT_EQ(model->nkey, 1);
  for (int j = 0; j < links; ++j) {
    EXPECT_NEAR(model->key_qpos[model->jnt_qposadr[id(model.get(), mjOBJ_JOINT, mujoco_joint_name(0, j))]],
                rig.frames[0].initial_angles_rad[j], 1e-16);
    EXPECT_EQ(model->key_qpos[model->jnt_qposadr[id(model.get(), mjOBJ_JOINT, mujoco_joint_name(1, j))]], 0);
  }
  // the contact: one frictionless pair of the tip spheres with the mapped, direct solref
  ASSERT_EQ(model->npair, 1);
  EXPECT_EQ(model->pair_dim[0], 1);
  EXPECT_LT(model->pair_solref[0], 0);
  EXPECT_LT(model->pair_solref[1], 0);
  for (int f = 0; f < 2; ++f) EXPECT_EQ(model->geom_contype[id(model.get(), mjOBJ_GEOM, mujoco_tip_geom_name(f))], 0);
}

TEST(MujocoModelExport, PairStiffnessIsTheLawsThroughMujocosInverseWeights) {
  const Scenario s = testing::paper_scenario("resonance");
  MujocoModelPtr model = load_from_file(mujoco_model_xml(s, settings(ContactLaw::viscoelastic, "matched")));
  ASSERT_TRUE(model);
  const mjModel* m = model.get();
  const int links = default_links(s);
  const double invweight = m->body_invweight0[2 * id(m, mjOBJ_BODY, mujoco_body_name(0, links - 1))] +
                           m->body_invweight0[2 * id(m, mjOBJ_BODY, mujoco_body_name(1, links - 1))];
  SolrefSolimp p;
  for (int i = 0; i < 2; ++i) p.solref[i] = m->pair_solref[i];
  for (int i = 0; i < 5; ++i) p.solimp[i] = m->pair_solimp[i];
  const SpringDashpot back = spring_dashpot_of(p, invweight);
  EXPECT_NEAR(back.stiffness_n_per_m / s.contact.viscoelastic->stiffness_n_per_m, 1, 1e-12);
  EXPECT_NEAR(back.damping_n_s_per_m / s.contact.viscoelastic->damping_n_s_per_m, 1, 1e-12);
  EXPECT_EQ(m->nkey, 0);  // the resonance case starts straight and at rest: no keyframe needed
}

TEST(MujocoModelExport, EachContactPathBuildsOnlyItsContact) {
  const Scenario s = testing::paper_scenario("resonance");
  struct Case {
    ContactLaw law;
    std::string path;
    int pairs;
    int tip_contype;  // 1: MuJoCo's own collision between the spheres (native)
  };
  for (const Case& c : {Case{ContactLaw::newton, "matched", 1, 0}, Case{ContactLaw::hertz, "matched", 0, 0},
                        Case{ContactLaw::viscoelastic, "injected", 0, 0}, Case{ContactLaw::hertz, "native", 0, 1}}) {
    SCOPED_TRACE(std::string(to_string(c.law)) + " " + c.path);
    RunSettings run = settings(c.law, c.path);
    run.options["integrator"] = "rk4";
    run.options["links"] = "4";
    MujocoModelPtr model = load_from_file(mujoco_model_xml(s, run));
    ASSERT_TRUE(model);
    expect_rig(model.get(), build_rig(s, c.law, 4), 4);
    EXPECT_EQ(model->opt.integrator, mjINT_RK4);
    EXPECT_EQ(model->npair, c.pairs);
    for (int f = 0; f < 2; ++f)
      EXPECT_EQ(model->geom_contype[id(model.get(), mjOBJ_GEOM, mujoco_tip_geom_name(f))], c.tip_contype);
    // native: MuJoCo's defaults, nothing set (solref 0.02 s critically damped, condim 3)
    if (c.path == "native") {
      const int g = id(model.get(), mjOBJ_GEOM, mujoco_tip_geom_name(0));
      EXPECT_EQ(model->geom_solref[mjNREF * g], 0.02);
      EXPECT_EQ(model->geom_solref[mjNREF * g + 1], 1);
      EXPECT_EQ(model->geom_condim[g], 3);
    }
  }
}

TEST(MujocoModelExport, RejectsBadOptionsAndNamesTheChain) {
  const Scenario s = testing::paper_scenario("resonance");
  const auto simulator = make_mujoco_simulator();
  EXPECT_EQ(simulator->name(), "mujoco");
  EXPECT_NE(simulator->version().find("2.2.2"), std::string::npos) << simulator->version();
  EXPECT_EQ(simulator->chain_links(s, RunSettings{}), default_links(s));
  RunSettings run;
  run.options = {{"links", "5"}};
  EXPECT_EQ(simulator->chain_links(s, run), 5);
  for (const auto& [name, value] : std::map<std::string, std::string>{{"integrator", "implicit"},
                                                                      {"contact", "soft"},
                                                                      {"links", "0"},
                                                                      {"newton_contact_steps", "1"},
                                                                      {"substeps", "2"}}) {
    RunSettings bad;
    bad.options = {{name, value}};
    EXPECT_THROW(mujoco_model_xml(s, bad), std::invalid_argument) << name << "=" << value;
    EXPECT_THROW(simulator->run(s, bad), std::invalid_argument) << name << "=" << value;
  }
}

}  // namespace mujoco_model_export_test
}  // namespace ib
