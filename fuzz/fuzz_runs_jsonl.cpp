// libFuzzer target: ib::fuzz::feed_runs_jsonl (entries.h says what it reads and what is a finding), in
// a folder of its own under $TMPDIR (scripts/fuzz.sh points it at /dev/shm).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp ? tmp : "/tmp") + "/fuzz_runs_jsonl." + std::to_string(getpid());
  }();
  ib::fuzz::feed_runs_jsonl(std::string_view(reinterpret_cast<const char*>(data), size), folder);
  return 0;
}
