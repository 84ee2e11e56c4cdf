// Every engine of the build says in provenance.json which build of its library ran (harness/records/provenance_file.h,
// Simulator::library_build): the file this process loaded, its size and SHA-256, the install prefix and the
// headers' version the adapter was compiled with. Each is checked against what the system says independently:
// the process's own mappings, stat, and sha256sum. Engines come from the catalog (catalog_engines.h).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "catalog_engines.h"
#include "harness/records/provenance_file.h"
#include "simulators/catalog.h"

namespace ib {
namespace engine_library_provenance_test {

namespace fs = std::filesystem;

// provenance.json's engine_builds as written into a folder of its own.
nlohmann::json written_engine_builds() {
  const fs::path dir = fs::temp_directory_path() / ("impactbench_engine_builds_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_provenance_file(dir.string(), simulator_catalog());
  std::ifstream in(dir / "provenance.json");
  const nlohmann::json provenance = nlohmann::json::parse(in);
  fs::remove_all(dir);
  return provenance.at("engine_builds");
}

// The hash as coreutils' sha256sum computes it: another program than the one under test.
std::string sha256sum_of(const std::string& path) {
  std::string quoted = "'";
  for (char c : path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  quoted += "'";
  std::string text;
  if (std::FILE* pipe = ::popen(("sha256sum -- " + quoted).c_str(), "r")) {
    char buffer[256];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
    ::pclose(pipe);
  }
  return text.substr(0, text.find(' '));
}

// Whether `path` is a file this process has mapped (/proc/self/maps): the library it loaded, not one it might find.
bool mapped_by_this_process(const std::string& path) {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);) {
    const std::size_t slash = line.find('/');
    if (slash != std::string::npos && fs::equivalent(line.substr(slash), path)) return true;
  }
  return false;
}

TEST(EngineLibraryProvenance, RecordsEveryEngineOfTheCatalog) {
  const nlohmann::json builds = written_engine_builds();
  const std::vector<std::string> engines = test::engines_among(simulator_names());
  ASSERT_FALSE(engines.empty()) << "a build without engines records none";
  EXPECT_EQ(builds.size(), engines.size()) << builds.dump(2);
  for (const std::string& engine : engines) EXPECT_TRUE(builds.contains(engine)) << engine;
}

TEST(EngineLibraryProvenance, TheLibraryFileIsTheLoadedOneWithItsSizeAndSha256) {
  const nlohmann::json builds = written_engine_builds();
  for (const std::string& engine : test::engines_among(simulator_names())) {
    SCOPED_TRACE(engine);
    const nlohmann::json& build = builds.at(engine);
    const std::string path = build.at("library_path");
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_TRUE(mapped_by_this_process(path)) << path;
    struct stat status {};
    ASSERT_EQ(::stat(path.c_str(), &status), 0) << path;
    EXPECT_EQ(build.at("library_size_bytes").get<long long>(), static_cast<long long>(status.st_size));
    const std::string expected_sha256 = sha256sum_of(path);
    ASSERT_EQ(expected_sha256.size(), 64u) << "sha256sum gave '" << expected_sha256 << "'";
    EXPECT_EQ(build.at("library_sha256").get<std::string>(), expected_sha256);
  }
}

TEST(EngineLibraryProvenance, NamesThePrefixAndTheHeadersVersionTheAdapterWasBuiltAgainst) {
  const nlohmann::json builds = written_engine_builds();
  for (const std::string& engine : test::engines_among(simulator_names())) {
    SCOPED_TRACE(engine);
    const nlohmann::json& build = builds.at(engine);
    EXPECT_FALSE(build.at("header_version").get<std::string>().empty());
    const std::string prefix = build.at("install_prefix");
    EXPECT_TRUE(fs::is_directory(prefix)) << "install_prefix '" << prefix << "'";
  }
}

}  // namespace engine_library_provenance_test
}  // namespace ib
