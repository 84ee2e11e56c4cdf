// DIR/provenance.json: what made a result folder's numbers, beside them, so that two folders can be put
// side by side knowing what differs between them before what moved (impactbench compare):
//   {"build": {"git_commit", "tracked_files_modified", "compiler", "build_type", "flags"},
//    "machine": {"cpu_model", "logical_cores", "memory_bytes", "os"},
//    "engines": {"<name>": "<its library's version>", ...},
//    "engine_builds": {"<name>": {"library_path", "library_size_bytes", "library_sha256", "install_prefix",
//                                 "header_version"}, ...}}
// engine_builds: which build of each engine's library ran (Simulator::library_build): the file this process
// loaded (found with dladdr, hashed with SHA-256), the prefix the adapter was built against and the version macro
// of the headers it was compiled with. Simulators without a library of their own (the reference) are not in it.
// The scenario files' digests are in the folder's suite.jsonl (a suite's settings) and sweep records.
#pragma once

#include <string>

#include "model/simulator.h"

namespace ib {

// The provenance of results this process makes with the simulators of `catalog`, as JSON text.
std::string provenance_json(const SimulatorCatalog& catalog);

// Writes provenance_json(catalog) to DIR/provenance.json (replacing an older one: the last command that
// wrote into the folder). Throws OutputError when the file cannot be written.
void write_provenance_file(const std::string& dir, const SimulatorCatalog& catalog);

// `impactbench --version`: impactbench's commit (and whether tracked files were modified), its build type, and
// each engine's library version, one per line: the short form of provenance.json.
std::string version_text(const SimulatorCatalog& catalog);

}  // namespace ib
