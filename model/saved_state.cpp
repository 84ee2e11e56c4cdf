#include "model/saved_state.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace ib {

void check_saved_state(const SavedState& state, const std::string& simulator, const std::string& layout) {
  if (state.simulator != simulator || state.layout != layout)
    throw std::invalid_argument("a saved state of '" + state.simulator + "' (" + state.layout +
                                ") cannot start a run of '" + simulator + "', which needs " + layout);
}

std::string saved_state_text(const SavedState& state) {
  std::string text = state.simulator + "\n" + state.layout + "\n";
  char buffer[40];
  for (double v : state.values) {
    std::snprintf(buffer, sizeof buffer, "%.17g\n", v);
    text += buffer;
  }
  return text;
}

SavedState parse_saved_state(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  SavedState state;
  if (!std::getline(in, state.simulator) || !std::getline(in, state.layout) || state.simulator.empty())
    throw std::invalid_argument(where +
                                ": a saved state starts with the simulator's name and its layout, one line each");
  std::string line;
  for (int number = 3; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(line.c_str(), &end);
    // strtod flags a subnormal result as a range error too, but the 17 digits the writer keeps name a
    // subnormal exactly: only an overflow (not finite) or an underflow to zero is out of range
    const bool out_of_range = errno == ERANGE && std::fpclassify(v) != FP_SUBNORMAL;
    if (end == line.c_str() || *end != '\0' || out_of_range || !std::isfinite(v))
      throw std::invalid_argument(where + " line " + std::to_string(number) + ": '" + line +
                                  "' is not a finite number (a saved state holds one value per line)");
    state.values.push_back(v);
  }
  return state;
}

}  // namespace ib
