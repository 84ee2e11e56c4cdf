#include "harness/records/number_text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ib {

namespace {
// Integers up to 2^53 are exact in a double; beyond, the value is not a count.
bool is_integer(double value) { return value == std::floor(value) && std::abs(value) < 9007199254740992.0; }
}  // namespace

std::string number_text(double value) {
  if (!std::isfinite(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, is_integer(value) ? "%.0f" : "%.9g", value);
  return text;
}

std::string exact_number_text(double value) {
  if (!std::isfinite(value)) return "";
  char text[32];
  for (int digits = 9; digits < 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) return text;
  }
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

nlohmann::ordered_json json_number(double value, bool exact) {
  if (!std::isfinite(value)) return nullptr;
  if (is_integer(value)) return static_cast<long long>(value);
  if (exact) return value;
  return std::strtod(number_text(value).c_str(), nullptr);
}

std::string csv_escape(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace ib
