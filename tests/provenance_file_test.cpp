// A result folder says what made it (harness/records/provenance_file.h): the build's commit, compiler, build
// type and flags, the machine, and every engine's library version, so that two folders can be compared
// knowing what differs. Checked against what this process can see for itself.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "harness/records/provenance_file.h"
#include "simulators/catalog.h"

namespace ib {
namespace provenance_file_test {

namespace fs = std::filesystem;

nlohmann::json written_provenance() {
  const fs::path dir = fs::temp_directory_path() / ("impactbench_provenance_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_provenance_file(dir.string(), simulator_catalog());
  std::ifstream in(dir / "provenance.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  fs::remove_all(dir);
  return j;
}

TEST(ProvenanceFile, NamesTheBuildItsCommitCompilerAndFlags) {
  const nlohmann::json build = written_provenance()["build"];
  const std::string commit = build["git_commit"];
  // a clone's commit (40 hex digits), or "unknown" for a tree without git
  const bool hex = commit.size() == 40 && commit.find_first_not_of("0123456789abcdef") == std::string::npos;
  EXPECT_TRUE(hex || commit == "unknown") << commit;
  EXPECT_TRUE(build["tracked_files_modified"].is_boolean());
#if defined(__GNUC__) && !defined(__clang__)
  EXPECT_EQ(build["compiler"].get<std::string>().rfind("GNU " + std::to_string(__GNUC__) + ".", 0), 0u)
      << build["compiler"];
#endif
  EXPECT_FALSE(build["build_type"].get<std::string>().empty());
#ifdef NDEBUG
  // every build type this project configures (Release, RelWithDebInfo) defines NDEBUG through its flags
  EXPECT_NE(build["flags"].get<std::string>().find("-DNDEBUG"), std::string::npos) << build["flags"];
#endif
}

TEST(ProvenanceFile, DescribesThisMachine) {
  const nlohmann::json machine = written_provenance()["machine"];
  EXPECT_EQ(machine["logical_cores"].get<unsigned>(), std::thread::hardware_concurrency());
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  long long kib = 0;
  meminfo >> key >> kib;  // "MemTotal: N kB", the first line
  ASSERT_EQ(key, "MemTotal:");
  EXPECT_EQ(machine["memory_bytes"].get<long long>(), kib * 1024);
  EXPECT_FALSE(machine["cpu_model"].get<std::string>().empty());
  EXPECT_EQ(machine["os"].get<std::string>().rfind("Linux ", 0), 0u) << machine["os"];
}

TEST(ProvenanceFile, GivesEveryEngineOfTheBuildWithItsLibrarysVersion) {
  const nlohmann::json engines = written_provenance()["engines"];
  const SimulatorCatalog catalog = simulator_catalog();
  EXPECT_EQ(engines.size(), catalog.names.size());
  for (const std::string& name : catalog.names) {
    ASSERT_TRUE(engines.contains(name)) << name;
    EXPECT_EQ(engines[name], catalog.make(name)->version()) << name;
    EXPECT_FALSE(engines[name].get<std::string>().empty()) << name;
  }
}

}  // namespace provenance_file_test
}  // namespace ib
