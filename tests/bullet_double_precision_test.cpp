// impactbench runs Bullet in double precision only: a 40 um indentation at 0.3 m from the origin is
// a few hundred float ulps (engines.md). Debian ships both builds under one header tree, so a
// single-precision Bullet would compile and link without complaint; the adapter's CMakeLists.txt
// refuses it at configure time, the adapter's sources static_assert it, and here it is checked at run
// time and the configure-time refusal is tried for real on a scratch project.
#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bullet_double_precision_test {

namespace fs = std::filesystem;

TEST(BulletDoublePrecision, BtScalarIsDouble) {
  EXPECT_EQ(sizeof(btScalar), 8u);
  EXPECT_TRUE(btIsDoublePrecision());
  EXPECT_EQ(btGetVersion(), 324);  // Bullet 3.24, the version engines.md describes
}

// Configures adapters/bullet/CMakeLists.txt alone (stand-ins for the project's other targets) against
// the given pkg-config module; returns CMake's exit code and output.
std::pair<int, std::string> configure_adapter_against(const std::string& module) {
  const fs::path root =
      fs::temp_directory_path() / ("impactbench_bullet_precision_" + std::to_string(::getpid()) + "_" + module);
  fs::remove_all(root);
  fs::create_directories(root);
  std::ofstream(root / "CMakeLists.txt") << "cmake_minimum_required(VERSION 3.18)\n"
                                            "project(bullet_precision_check CXX)\n"
                                            "add_library(impactbench_adapter_common INTERFACE)\n"
                                            "add_library(impactbench_model INTERFACE)\n"
                                            "add_subdirectory(\"" IMPACTBENCH_SOURCE_DIR "/adapters/bullet\" bullet)\n";
  const fs::path log = root / "configure.log";
  const std::string command = "cmake -S \"" + root.string() + "\" -B \"" + (root / "build").string() +
                              "\" -DIMPACTBENCH_BULLET_PKG=" + module + " > \"" + log.string() + "\" 2>&1";
  const int status = std::system(command.c_str());
  std::stringstream output;
  output << std::ifstream(log).rdbuf();
  fs::remove_all(root);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output.str()};
}

TEST(BulletDoublePrecision, ConfiguringAgainstTheSinglePrecisionBuildFails) {
  if (std::system("cmake --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "cmake is not on PATH";
  // the set-up itself works: the double-precision package configures
  const auto [double_status, double_output] = configure_adapter_against("bullet-float64");
  ASSERT_EQ(double_status, 0) << double_output;
  EXPECT_NE(double_output.find("double precision"), std::string::npos) << double_output;
  // Debian's plain "bullet" module is the single-precision build: refused, with the reason
  const auto [single_status, single_output] = configure_adapter_against("bullet");
  EXPECT_NE(single_status, 0) << single_output;
  EXPECT_NE(single_output.find("CMake Error"), std::string::npos) << single_output;
  EXPECT_NE(single_output.find("single precision"), std::string::npos) << single_output;
  EXPECT_NE(single_output.find("sizeof(btScalar) != 8"), std::string::npos) << single_output;
  EXPECT_NE(single_output.find("bullet-float64"), std::string::npos) << single_output;
}

}  // namespace bullet_double_precision_test
