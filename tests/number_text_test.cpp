// How the result files write numbers and text cells (harness/records/number_text.h): one rule for every writer.
#include "harness/records/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

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
