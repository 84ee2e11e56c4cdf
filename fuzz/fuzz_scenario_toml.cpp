// libFuzzer target: ib::fuzz::feed_scenario_toml (entries.h says what it reads and what is a finding).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ib::fuzz::feed_scenario_toml(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
