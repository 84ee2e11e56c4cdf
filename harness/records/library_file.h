// The file a library was loaded from in this process, with its size and content hash: what provenance.json
// records of each engine (harness/records/provenance_file.h), because a version string alone does not tell two
// builds of one version apart (a patched, rebuilt or locally installed library).
#pragma once

#include <string>

namespace ib {

struct LibraryFile {
  std::string path;           // the loaded file, symbolic links resolved; "" when dladdr cannot say
  long long size_bytes = -1;  // -1 when the file cannot be read
  std::string sha256;         // 64 lowercase hex digits; "" when the file cannot be read
};

// The file holding `function` (a function of a shared library, or of the executable itself when the library
// was linked statically), found with dladdr in this process's own mappings.
LibraryFile loaded_library_file(const void* function);

// The SHA-256 of the file at `path` as 64 lowercase hex digits (OpenSSL's libcrypto); "" when it cannot be read.
std::string file_sha256(const std::string& path);

}  // namespace ib
