#include "harness/records/provenance_file.h"

#include <sys/utsname.h>

#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "harness/records/library_file.h"
#include "harness/records/run_files.h"
#include "impactbench_build_info.h"  // generated at build time (cmake/provenance_header.cmake)

namespace ib {

namespace {

using Json = nlohmann::ordered_json;

// The text after "KEY:" on the first line of FILE that starts with KEY, trimmed ("" when there is none).
std::string proc_field(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "" : line.substr(start);
  }
  return "";
}

Json machine_json() {
  // /proc/meminfo gives "MemTotal:  24576000 kB"
  long long memory_bytes = 0;
  try {
    memory_bytes = std::stoll(proc_field("/proc/meminfo", "MemTotal")) * 1024;
  } catch (const std::exception&) {
    memory_bytes = 0;  // not Linux, or unreadable: said as 0, not guessed
  }
  utsname system{};
  const std::string os = uname(&system) == 0 ? std::string(system.sysname) + " " + system.release : "";
  return {{"cpu_model", proc_field("/proc/cpuinfo", "model name")},
          {"logical_cores", std::thread::hardware_concurrency()},
          {"memory_bytes", memory_bytes},
          {"os", os}};
}

Json build_json() {
  return {{"git_commit", build_info::kGitCommit},
          {"tracked_files_modified", build_info::kTrackedFilesModified},
          {"compiler", build_info::kCompiler},
          {"build_type", build_info::kBuildType},
          {"flags", build_info::kFlags}};
}

// The build of each simulator's library that this process runs; library_size_bytes -1 and library_sha256 ""
// say that the file could not be read (written as found, not left out, so that a comparison shows it).
Json engine_builds_json(const SimulatorCatalog& catalog) {
  Json builds = Json::object();
  for (const std::string& name : catalog.names) {
    const LibraryBuild build = library_build_of(catalog, name);
    if (!build.library_function) continue;
    const LibraryFile file = loaded_library_file(build.library_function);
    builds[name] = {{"library_path", file.path},
                    {"library_size_bytes", file.size_bytes},
                    {"library_sha256", file.sha256},
                    {"install_prefix", build.install_prefix},
                    {"header_version", build.header_version}};
  }
  return builds;
}

}  // namespace

std::string provenance_json(const SimulatorCatalog& catalog) {
  Json engines = Json::object();
  for (const std::string& name : catalog.names) engines[name] = version_of(catalog, name);
  return Json{{"build", build_json()},
              {"machine", machine_json()},
              {"engines", engines},
              {"engine_builds", engine_builds_json(catalog)}}
             .dump(2) +
         "\n";
}

void write_provenance_file(const std::string& dir, const SimulatorCatalog& catalog) {
  replace_text_file(dir + "/provenance.json", provenance_json(catalog));
}

std::string version_text(const SimulatorCatalog& catalog) {
  std::string text = std::string("impactbench ") + build_info::kGitCommit +
                     (build_info::kTrackedFilesModified ? " (tracked files modified)" : "") + ", " +
                     build_info::kBuildType + " build\n";
  for (const std::string& name : catalog.names) text += "  " + name + ": " + version_of(catalog, name) + "\n";
  return text;
}

}  // namespace ib
