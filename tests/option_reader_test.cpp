// An engine's options are read through one OptionReader (model/simulator_options.h): a value it refuses
// gets a message naming the engine, the option, the value and what is allowed, with the bounds written as a
// person writes them.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "model/simulator_options.h"

namespace ib {
namespace option_reader_test {

const std::vector<std::pair<std::string, std::string>> kAllowed = {
    {"links", "links per frame"}, {"erp", "error reduction"}, {"contact", "path"}};

// The message OptionReader gives for name=value read as what `read` asks, or "" when it accepts it.
template <typename Read>
std::string message(const std::string& name, const std::string& value, Read read) {
  try {
    read(OptionReader("someengine", {{name, value}}, kAllowed));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string links_message(const std::string& value) {
  return message("links", value, [](const OptionReader& r) { r.integer("links", 8, 1, 64); });
}
std::string erp_message(const std::string& value) {
  return message("erp", value, [](const OptionReader& r) { r.number("erp", 0.2, 0.001, 1); });
}

TEST(OptionReader, AnIntegerOutOfRangeOrFractionalNamesItsIntegerBounds) {
  const std::string expected = "someengine option links=%: allowed: an integer from 1 to 64";
  for (const std::string value : {"0", "65", "2.5", "eight", "nan", ""}) {
    std::string text = expected;
    text.replace(text.find('%'), 1, value);
    EXPECT_EQ(links_message(value), text) << value;
  }
  EXPECT_EQ(links_message("64"), "");
  EXPECT_EQ(OptionReader("someengine", {{"links", "12"}}, kAllowed).integer("links", 8, 1, 64), 12);
  EXPECT_EQ(OptionReader("someengine", {}, kAllowed).integer("links", 8, 1, 64), 8);
}

TEST(OptionReader, ANumberOutOfRangeNamesItsBoundsAsWritten) {
  EXPECT_EQ(erp_message("2"), "someengine option erp=2: allowed: a number from 0.001 to 1");
  EXPECT_EQ(erp_message("0.1x"), "someengine option erp=0.1x: allowed: a number from 0.001 to 1");
  EXPECT_EQ(erp_message("inf"), "someengine option erp=inf: allowed: a number from 0.001 to 1");
  EXPECT_EQ(erp_message("0.001"), "");
  EXPECT_DOUBLE_EQ(OptionReader("someengine", {{"erp", "0.5"}}, kAllowed).number("erp", 0.2, 0.001, 1), 0.5);
}

TEST(OptionReader, AnUnknownOptionIsRefusedNamingTheKnownOnes) {
  const std::string text = message("damping", "1", [](const OptionReader&) {});
  EXPECT_NE(text.find("someengine"), std::string::npos) << text;
  EXPECT_NE(text.find("damping"), std::string::npos) << text;
  EXPECT_NE(text.find("links"), std::string::npos) << text;
}

}  // namespace option_reader_test
}  // namespace ib
