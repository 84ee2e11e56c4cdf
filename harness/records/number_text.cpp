#include "harness/records/number_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <system_error>

namespace ib {

namespace {
// Integers up to 2^53 are exact in a double; beyond, the value is not a count.
bool is_integer(double value) { return value == std::floor(value) && std::abs(value) < 9007199254740992.0; }

// printf's "%.{digits}g" (std::to_chars is specified as printf with that format, the same text) without
// printf's cost: a run writes millions of these, and printf's general formatting was a large part of a run.
std::string general_text(double value, int digits) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, value, std::chars_format::general, digits);
  return std::string(text, written.ptr);
}

double read_back(const std::string& text) {
  double value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}
}  // namespace

std::string number_text(double value) {
  if (!std::isfinite(value)) return "";
  if (!is_integer(value)) return general_text(value, 9);
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed, 0);
  return std::string(text, written.ptr);
}

// The digits of the shortest text that reads back as the value (std::to_chars without a precision).
int shortest_digit_count(double value) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, value, std::chars_format::scientific);
  int digits = 0;
  for (const char* c = text; c < written.ptr && *c != 'e'; ++c) digits += *c >= '0' && *c <= '9';
  return digits;
}

std::string exact_number_text(double value) {
  if (!std::isfinite(value)) return "";
  // "%.Ng" with the least N >= 9 that reads back: no N below the shortest text's digit count does, and that
  // count (or 9) does unless the value sits at a binade's edge, where the search below decides. One
  // formatting instead of a formatting and a reading per digit: a series writes a time per sample.
  const std::string first = general_text(value, std::max(9, shortest_digit_count(value)));
  if (read_back(first) == value) return first;
  for (int digits = 9; digits < 17; ++digits) {
    std::string text = general_text(value, digits);
    if (read_back(text) == value) return text;
  }
  return general_text(value, 17);
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
