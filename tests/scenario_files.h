// Scenario files as the scenario tests read them: the published files, the malformed corpus
// (tests/data/malformed_scenarios), a published file with one line replaced, and the ScenarioError a load throws.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "model/scenario_toml.h"

namespace ib::testing {

inline const std::string kPaperDir = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper";
inline const std::string kMalformedDir = std::string(IMPACTBENCH_TEST_DATA_DIR) + "/malformed_scenarios";

inline std::string paper_file(const std::string& name) { return kPaperDir + "/" + name + ".toml"; }
inline std::string malformed_file(const std::string& name) { return kMalformedDir + "/" + name + ".toml"; }

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The text of a paper file with line `line` (1-based) replaced by `replacement` (which may hold
// several lines, or be empty to leave a blank line).
inline std::string paper_text_with(const std::string& name, int line, const std::string& replacement) {
  std::istringstream in(read_text(paper_file(name)));
  std::string out, current;
  for (int n = 1; std::getline(in, current); ++n) out += (n == line ? replacement : current) + "\n";
  return out;
}

// The ScenarioError thrown by `load`, or a failed test if none is thrown.
template <class Load>
ScenarioError error_from(Load load) {
  try {
    load();
  } catch (const ScenarioError& error) {
    return error;
  }
  ADD_FAILURE() << "no ScenarioError thrown";
  return ScenarioError("", 0, "", "");
}

}  // namespace ib::testing
