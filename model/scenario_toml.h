// Reading scenario files (TOML; the format of scenarios/paper/*.toml). Every key is checked against
// one schema table in scenario_toml.cpp: its type, its allowed range and its unit. Any mistake stops
// the load with a message that names the file, the line, the dotted key, the value found and what is
// allowed, e.g.
//   scenarios/x.toml:18: frame1.tip_mass_kg = -1: out of range; allowed: >= 0 (tip mass [kg])
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "model/scenario.h"

namespace ib {

// Thrown for any bad scenario input; what() is the full message:
//   "<path>:<line>: <message>"           a mistake in the file
//   "<path>:<line>:<column>: <message>"  a TOML syntax error
//   "<path>: <message>"                  no line applies (the file cannot be read)
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string path, int line, std::string key, std::string message, int column = 0);

  const std::string& path() const { return path_; }
  int line() const { return line_; }                       // 1-based; 0 when no line applies
  int column() const { return column_; }                   // 1-based for syntax errors; 0 otherwise
  const std::string& key() const { return key_; }          // dotted key, e.g. "frame1.tip_mass_kg"; "" if none
  const std::string& message() const { return message_; }  // what() without the "<path>:<line>: "

 private:
  std::string path_;
  int line_;
  int column_;
  std::string key_;
  std::string message_;
};

// The text of a TOML input file (a scenario, an uncertain-inputs file): a regular file of at most 1 MB. Anything
// else, or a file that cannot be read, gives a ScenarioError naming the path: "cannot read WHAT: why".
std::string read_toml_file(const std::string& path, const std::string& what);

// Reads and checks a scenario file; an unreadable file gives a ScenarioError naming the path.
Scenario load_scenario(const std::string& path);

// Checks scenario text; source_path is used in messages and stored in Scenario::source_path.
Scenario parse_scenario(std::string_view toml_text, const std::string& source_path);

// Every *.toml file below a folder (recursively), sorted, but *_inputs.toml (a validation's uncertain inputs,
// model/uncertain_inputs.h). A missing folder gives a ScenarioError.
std::vector<std::string> find_scenario_files(const std::string& folder);

}  // namespace ib
