// What a study file's part gives, in the terms of the command it stands for (cli/study_file.cpp reads it), and
// the helpers its readers share: cli/study_file.cpp for suites, searches and sweeps, cli/study_validation.cpp
// for validations.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "harness/study/study.h"
#include "model/toml_schema.h"

namespace cli {

// A part as its table gives it, in the terms of the command it stands for: what the options' checks read.
struct PartOptions {
  ib::StudyPartKind kind = ib::StudyPartKind::suite;
  std::string name;        // a sweep's: its folder below OUT/sweeps/; a suite's or search's: for messages
  std::string file;        // the study file
  int line = 0;            // its table's header ([[suite]], [[search]], [[sweep]])
  SuiteOptions suite;      // suite and search
  SweepOptions sweep;      // sweep
  std::string inputs;      // validation: its uncertain-inputs file
  int points = 64;         // validation: sample points per case
  int nominal_starts = 8;  // validation: the nominal cases' starts (their chaos)
  MeasurementOptions measurement;
  std::map<std::string, int> key_lines;  // each key given, by its line: messages about a value name it
  std::map<std::string, std::vector<std::string>> key_items;  // an array key's items, as given (a comma in one stays)
};

// The keys a part gives, as its table (or [defaults]) holds them: key -> the command's option text.
using GivenKeys = std::map<std::string, std::string>;

// A relative scenario path: from the study file's folder if it names a file or folder there, else from the
// project's folder.
std::string scenario_path(const std::string& study_file, const std::string& path);

// Fails (naming the key's line) unless the part's name can be its folder below OUT/KIND/: required, 1 or more of
// a-z, 0-9, _ and - (a sweep's, a validation's).
void require_folder_name(const ib::toml_schema::Checker& checker, const GivenKeys& given, PartOptions& part,
                         const std::string& dotted, const std::string& folder_below);

// Fails (naming the part's header line) when `key` is not given; `meaning` says what is allowed.
void require_key(const ib::toml_schema::Checker& checker, const GivenKeys& given, const PartOptions& part,
                 const std::string& dotted, const char* key, const char* meaning);

}  // namespace cli
