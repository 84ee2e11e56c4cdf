// A continuation's saved state (model/saved_state.h) written as text and read back is the same state to the
// bit: a sweep's chain continues from each ratio's state.txt, and a resumed chain (docs/sweeps.md) from the one
// it reads back from disk, so a value that came back one unit in the last place off would make a resumed sweep
// differ from an uninterrupted one from that ratio on (the reference continues a run exactly: sweep_test).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "harness/records/run_files.h"
#include "harness/sweep/sweep_internal.h"
#include "model/saved_state.h"

namespace ib {
namespace saved_state_round_trip_test {

// Values whose shortest exact decimal form has 17 significant digits: 16 digits name another double. The
// kind of number a modal coordinate or a joint velocity is after a long run: a sum that rounded, a quotient,
// a neighbour of a round number.
std::vector<double> values_that_need_17_digits() {
  return {
      0.1 + 0.2,                        // 0.30000000000000004
      std::nextafter(1.0, 2.0),         // 1 + 2^-52
      std::nextafter(0.5, 0.0),         // 0.49999999999999994
      -std::nextafter(0.001, 1.0),      // a tip displacement one ulp past 1 mm
      1e-5 / 3,                         // a modal coordinate [sqrt(kg) m]
      -0.05 * std::sqrt(2.0) / 3,       // a tip velocity [m/s]
      1.1 * 1.1,                        // 1.2100000000000002
      std::nextafter(123456.789, 0.0),  // a motor angle [rad] after a long run
  };
}

// The values a state can hold at the edges of the doubles: the sign of a zero (a velocity that reached 0 from
// below), the largest and smallest normal magnitudes, and subnormals (a damped mode's coordinate far down its
// decay), which strtod reads exactly but flags as an underflow.
std::vector<double> edge_values() {
  return {0.0, -0.0, DBL_MAX, -DBL_MAX, DBL_MIN, -DBL_MIN, std::nextafter(DBL_MIN, 0.0), -DBL_TRUE_MIN, 1e-310};
}

// The value written with `digits` significant digits and read back.
double read_back_with_digits(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return std::strtod(text, nullptr);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

SavedState state_of(const std::vector<double>& values) {
  return SavedState{"reference", "modal q then v of 20 modes (beam)", values};
}

// The test's own inputs: without the 17th digit each of these comes back a different double, so a writer
// that kept fewer digits would fail the round trips below.
TEST(SavedStateRoundTrip, TheTestValuesCannotSurviveSixteenDigits) {
  for (double v : values_that_need_17_digits()) {
    EXPECT_FALSE(same_bits(read_back_with_digits(v, 16), v)) << v << " survives 16 digits";
    EXPECT_TRUE(same_bits(read_back_with_digits(v, 17), v)) << v;
  }
}

void expect_same_state(const SavedState& read, const SavedState& written) {
  EXPECT_EQ(read.simulator, written.simulator);
  EXPECT_EQ(read.layout, written.layout);
  ASSERT_EQ(read.values.size(), written.values.size());
  for (std::size_t i = 0; i < written.values.size(); ++i) {
    char bits[64];
    std::snprintf(bits, sizeof bits, "%a written, %a read", written.values[i], read.values[i]);
    EXPECT_TRUE(same_bits(read.values[i], written.values[i])) << "value " << i << ": " << bits;
  }
}

TEST(SavedStateRoundTrip, TextReadBackIsTheStateToTheBit) {
  std::vector<double> values = values_that_need_17_digits();
  for (double v : edge_values()) values.push_back(v);
  const SavedState written = state_of(values);
  expect_same_state(parse_saved_state(saved_state_text(written), "state.txt"), written);
}

// The path a resumed sweep takes: the row's state.txt written as a finished ratio writes it (sweep_row.cpp),
// then read from its folder by the chain that continues.
TEST(SavedStateRoundTrip, ARowsStateFileReadBackByTheResumedChainIsTheStateToTheBit) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(::testing::TempDir()) / ("saved_state_round_trip_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const SavedState written = state_of(values_that_need_17_digits());
  replace_text_file((folder / "state.txt").string(), saved_state_text(written));
  const std::optional<SavedState> read = sweep_internal::read_row_state(folder.string());
  fs::remove_all(folder);
  ASSERT_TRUE(read.has_value());
  expect_same_state(*read, written);
}

}  // namespace saved_state_round_trip_test
}  // namespace ib
