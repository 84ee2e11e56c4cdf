// MuJoCo's errors and warnings never end the process and never leave MUJOCO_LOG.TXT behind: an
// mju_error raised inside MuJoCo's C code arrives as a MujocoError exception, a warning is counted and
// named with MuJoCo's text, a run whose state MuJoCo flags ends unstable with that warning as its
// reason, and a model that does not compile is an error with MuJoCo's message. Every test runs in a
// fresh working directory and checks that it is still empty afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "adapters/mujoco/mujoco_engine.h"
#include "adapters/mujoco/mujoco_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace mujoco_error_handling_test {

namespace fs = std::filesystem;

const char* kOneHinge =
    "<mujoco><worldbody><body><joint type=\"hinge\" axis=\"0 1 0\"/>"
    "<inertial pos=\"0 0 0.1\" mass=\"1\" diaginertia=\"1e-3 1e-3 1e-3\"/></body></worldbody></mujoco>";

class MujocoErrorHandling : public ::testing::Test {
 protected:
  void SetUp() override {
    previous_ = fs::current_path();
    folder_ = fs::temp_directory_path() / ("impactbench_mujoco_errors_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    fs::current_path(folder_);
  }
  void TearDown() override {
    fs::current_path(previous_);
    EXPECT_TRUE(fs::is_empty(folder_)) << "MuJoCo left a file in the working directory";
    EXPECT_FALSE(fs::exists(folder_ / "MUJOCO_LOG.TXT"));
    fs::remove_all(folder_);
  }
  fs::path previous_, folder_;
};

TEST_F(MujocoErrorHandling, ErrorInsideMujocoBecomesAnException) {
  install_mujoco_handlers();
  MujocoModelPtr model = compile_mjcf(kOneHinge);
  MujocoDataPtr data = make_data(model.get());
  // mj_stackAlloc raises mju_error from MuJoCo's C code when the stack is too small
  EXPECT_THROW(mj_stackAlloc(data.get(), 1 << 30), MujocoError);
  try {
    mju_malloc(std::size_t{1} << 62);  // raises "Could not allocate memory"
    ADD_FAILURE() << "mju_malloc returned";
  } catch (const MujocoError& error) {
    EXPECT_NE(std::string(error.what()).find("allocate"), std::string::npos) << error.what();
  }
}

TEST_F(MujocoErrorHandling, WarningIsNamedWithMujocosText) {
  MujocoModelPtr model = compile_mjcf(kOneHinge);
  MujocoDataPtr data = make_data(model.get());
  MujocoWarningWatch watch(data.get());
  EXPECT_EQ(watch.new_warning(0), "");
  data->qvel[0] = NAN;
  mj_checkVel(model.get(), data.get());  // warns and resets the state, as inside mj_step
  const std::string warning = watch.new_warning(0.25);
  EXPECT_NE(warning.find("mjWARN_BADQVEL"), std::string::npos) << warning;
  EXPECT_NE(warning.find("t = 0.25 s"), std::string::npos) << warning;
  EXPECT_NE(warning.find("QVEL"), std::string::npos) << warning;  // MuJoCo's own words
  EXPECT_EQ(watch.new_warning(0.25), "");                         // reported once
}

TEST_F(MujocoErrorHandling, ModelThatDoesNotCompileIsAnError) {
  try {
    compile_mjcf("<mujoco><worldbody><body><joint type=\"ball-and-socket\"/></body></worldbody></mujoco>");
    ADD_FAILURE() << "compiled";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("MuJoCo could not compile"), std::string::npos) << error.what();
  }
}

// A motor at 1 MHz pushes the tip with about 4e9 N on the first step: MuJoCo flags the acceleration
// (mjWARN_BADQACC) before any displacement bound is reached, and the run reports exactly that.
TEST_F(MujocoErrorHandling, RunFlaggedByMujocoEndsUnstableWithTheWarning) {
  Scenario s = testing::paper_scenario("resonance");
  s.duration_s = 0.01;
  s.scoring_window_s = 0.01;
  s.motor->speed_ratio_to_f1.reset();
  s.motor->frequency_hz = 1e6;
  RunSettings run;
  run.law = ContactLaw::viscoelastic;
  const RunResult result = make_mujoco_simulator()->run(s, run);
  EXPECT_EQ(result.status, RunStatus::unstable);
  EXPECT_NE(result.reason.find("mjWARN_BADQACC"), std::string::npos) << result.reason;
  std::printf("reason: %s\n", result.reason.c_str());
}

}  // namespace mujoco_error_handling_test
}  // namespace ib
