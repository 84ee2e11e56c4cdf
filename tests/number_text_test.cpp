// How the result files write numbers and text cells (harness/records/number_text.h): one rule for every writer.
#include "harness/records/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace ib {
namespace number_text_test {

TEST(NumberText, MeasuredValuesHaveNineDigitsCountsAreWholeAndNonFiniteIsEmpty) {
  EXPECT_EQ(number_text(0.123456789123), "0.123456789");
  EXPECT_EQ(number_text(140000), "140000");
  EXPECT_EQ(number_text(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(number_text(std::numeric_limits<double>::infinity()), "");
}

TEST(NumberText, ExactTextReadsBackAsTheSameDouble) {
  for (double t : {0.1 + 0.2, 10.000244140625, 1.0 / 3.0, 6.25e-05, 12.80645}) {
    const std::string text = exact_number_text(t);
    EXPECT_EQ(std::stod(text), t) << text;
  }
  EXPECT_EQ(exact_number_text(0.45380000000000004), "0.45380000000000004");
}

// The text is printf's "%.Ng" with the least N >= 9 that reads back, whatever the value: sample times on a
// 4096 Hz grid, values at a power of two's edge, tiny and huge ones.
TEST(NumberText, ExactTextIsTheLeastPrecisionFromNineThatReadsBack) {
  auto least_precision_text = [](double value) {
    char text[64];
    for (int digits = 9; digits < 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, value);
      if (std::strtod(text, nullptr) == value) return std::string(text);
    }
    std::snprintf(text, sizeof text, "%.17g", value);
    return std::string(text);
  };
  std::vector<double> values = {0.0, -0.0, 1.0, 0.5, 86.0 + 1.0 / 4096, 1e-300, -2.5e300, 5e-324, 9007199254740993.0};
  for (int k = 0; k < 20000; ++k) values.push_back(86.0 + k / 4096.0);
  for (int e = -60; e <= 60; ++e) {
    const double p = std::ldexp(1.0, e);
    values.insert(values.end(), {p, std::nextafter(p, 0.0), std::nextafter(p, 1e308), -p / 3});
  }
  unsigned state = 12345;
  for (int k = 0; k < 20000; ++k) {
    state = state * 1103515245u + 12345u;
    values.push_back(std::ldexp(1.0 + state / 4294967296.0, static_cast<int>(state % 200) - 100));
  }
  for (double v : values) ASSERT_EQ(exact_number_text(v), least_precision_text(v)) << v;
}

// A measured value's text is printf's "%.9g", whatever the value: ties in the tenth digit, roundings that carry
// into a new digit, every exponent where %g switches between fixed and scientific.
TEST(NumberText, MeasuredTextIsPrintfsNineDigits) {
  auto printf_text = [](double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", value);
    return std::string(text);
  };
  std::vector<double> values = {0.5,           -0.25,          1.0000000005, 1.0000000015,
                                0.99999999951, 9.9999999951,   999999999.5,  1.23456789012345e-5,
                                1.23456789e-4, 9.999999995e-5, 123456789.4,  5e-324,
                                1.5e300};
  for (int e = -320; e <= 300; ++e) {
    const double p = std::pow(10.0, e);
    values.insert(values.end(),
                  {p, std::nextafter(p, 0.0), std::nextafter(p, 1e308), 0.99999999951 * p, 1.0000000005 * p, -p / 3});
  }
  for (int k = 0; k < 2000; ++k) {  // ties in the shortest text: ten digits, the last a 5
    char tie[32];
    std::snprintf(tie, sizeof tie, "%d.%08d5e%d", 1 + k % 9, k * 4999 % 100000000, k % 40 - 20);
    values.push_back(std::strtod(tie, nullptr));
  }
  unsigned state = 2468;
  for (int k = 0; k < 200000; ++k) {
    state = state * 1103515245u + 12345u;
    const double mantissa = 1.0 + state / 4294967296.0;
    state = state * 1103515245u + 12345u;
    values.push_back((state & 1 ? -1 : 1) * std::ldexp(mantissa, static_cast<int>(state % 140) - 70));
  }
  for (double v : values) {
    if (v == std::floor(v) && std::abs(v) < 9007199254740992.0) continue;  // counts: written whole
    ASSERT_EQ(number_text(v), printf_text(v)) << std::hexfloat << v;
  }
}

TEST(NumberText, JsonNumbersAreNullIntegerRoundedOrExact) {
  EXPECT_TRUE(json_number(std::nan("")).is_null());
  EXPECT_TRUE(json_number(35).is_number_integer());
  EXPECT_EQ(json_number(0.123456789123).get<double>(), 0.123456789);
  EXPECT_EQ(json_number(0.1 + 0.2, true).get<double>(), 0.1 + 0.2);
}

TEST(NumberText, ACsvCellWithACommaQuoteOrLineBreakIsQuoted) {
  EXPECT_EQ(csv_escape("contact=matched"), "contact=matched");
  EXPECT_EQ(csv_escape("off by 12 %, against the beam"), "\"off by 12 %, against the beam\"");
  EXPECT_EQ(csv_escape("say \"no\""), "\"say \"\"no\"\"\"");
  EXPECT_EQ(csv_escape("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_escape(""), "");
}

}  // namespace number_text_test
}  // namespace ib
