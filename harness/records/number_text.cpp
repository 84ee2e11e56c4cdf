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

// "%.9g" without to_chars's exact decimal expansion: the value scaled by a power of ten that a double holds
// exactly (one rounding, half an ulp: under 1e-7 of the last digit) and rounded to a nine-digit integer. That
// rounding is the exact one unless the scaled value lies within 1e-6 of a half, where the scaling's error could
// decide it: there, and for magnitudes the table does not reach, printf's own rounding decides.
std::string nine_digit_text(double value) {
  static constexpr double kPowers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                       1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const double magnitude = std::abs(value);
  int exponent = static_cast<int>(std::floor(std::log10(magnitude)));  // may be off by one: checked below
  double scaled = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int shift = 8 - exponent;
    if (shift < -22 || shift > 22) return general_text(value, 9);
    scaled = shift >= 0 ? magnitude * kPowers[shift] : magnitude / kPowers[-shift];
    if (scaled >= 1e9)
      ++exponent;
    else if (scaled < 1e8)
      --exponent;
    else
      break;
  }
  const double whole = std::floor(scaled);
  if (!(scaled >= 1e8 && scaled < 1e9) || std::abs(scaled - whole - 0.5) < 1e-6) return general_text(value, 9);
  long long digits_value = static_cast<long long>(whole) + (scaled - whole > 0.5 ? 1 : 0);
  if (digits_value == 1000000000) digits_value = 100000000, ++exponent;  // 9.99999999|6 -> 1.00000000e+1
  char digits[9];
  for (int i = 8; i >= 0; --i, digits_value /= 10) digits[i] = static_cast<char>('0' + digits_value % 10);
  int count = 9;
  while (count > 1 && digits[count - 1] == '0') --count;
  char text[32];
  char* out = text;
  if (value < 0) *out++ = '-';
  if (exponent < -4 || exponent >= 9) {  // printf's %g: scientific, the exponent with at least two digits
    *out++ = digits[0];
    if (count > 1) {
      *out++ = '.';
      for (int i = 1; i < count; ++i) *out++ = digits[i];
    }
    *out++ = 'e';
    *out++ = exponent < 0 ? '-' : '+';
    const int e = std::abs(exponent);
    if (e >= 100) *out++ = static_cast<char>('0' + e / 100);
    *out++ = static_cast<char>('0' + e / 10 % 10);
    *out++ = static_cast<char>('0' + e % 10);
  } else if (exponent < 0) {
    *out++ = '0';
    *out++ = '.';
    for (int i = 0; i < -exponent - 1; ++i) *out++ = '0';
    for (int i = 0; i < count; ++i) *out++ = digits[i];
  } else {
    for (int i = 0; i <= exponent; ++i) *out++ = i < count ? digits[i] : '0';
    if (count > exponent + 1) {
      *out++ = '.';
      for (int i = exponent + 1; i < count; ++i) *out++ = digits[i];
    }
  }
  return std::string(text, out);
}

double read_back(const std::string& text) {
  double value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}
}  // namespace

std::string number_text(double value) {
  if (!std::isfinite(value)) return "";
  if (!is_integer(value)) return nine_digit_text(value);
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
